// The GPU relight view (web/views/gpu_view.h) in two modes: mode=tree relights
// from the wavelet-tree textures (view_tree.js, Boulton §4.5), mode=4d from
// the 4D store's own arrays (view_4d.js, the 4D paper's Eq. 8). Both draw
// into one W×H RGBA32F frame (alpha 0 on masked cells) that display.frag
// shows and the contract reads back. No pixels cross the network: per
// change of probe, rotation or term count only the lighting (environment
// trees or kept lights, a few KB) does; exposure is a display uniform.
//
// Testability contract: once a frame is drawn, document.body.dataset.gpuReady
// is "1" and window.wavebakeGpuFrame() returns {width, height, data}: data a
// Float32Array of linear RGB, row 0 at the top, NaN where masked — the shape
// of the Python module's wavebake.relight(Store, probe, terms, rotate).
// window.wavebakeGpuBench(frames) redraws the current lighting `frames`
// times and returns {mode, device, msPerFrame, bytesOnGpu, work}. For uv
// stores the canvas shows the lightmapped mesh in 3D (view_mesh.js; &view=flat
// or the checkbox for the flat lightmap); window.wavebakeOrbit(dyaw, dpitch,
// zoom) turns its camera.
"use strict";

(async function () {
  const G = window.WavebakeGL;
  const params = new URLSearchParams(location.search);
  const state = {
    store: Number(params.get("store") || 0),
    probe: params.get("probe") || "builtin:sky",
    rotate: Number(params.get("rotate") || 0),
    terms: Number(params.get("terms") || 256),
    mode: params.get("mode") || "tree",
    exposure: Number(params.get("exposure") || 0),
  };
  const $ = (id) => document.getElementById(id);
  const status = $("status");
  const fail = (message) => {
    status.textContent = message;
    document.body.dataset.gpuError = message;
  };
  document.body.dataset.gpuReady = "0";
  document.body.dataset.gpuFrames = "0";

  const canvas = $("view");
  const gl = canvas.getContext("webgl2", { antialias: false, preserveDrawingBuffer: true });
  if (!gl) return fail("WebGL2 is not available in this browser");
  if (!gl.getExtension("EXT_color_buffer_float"))
    return fail("EXT_color_buffer_float is missing: no float render target");
  const modes = { tree: window.WavebakeTreeMode, "4d": window.WavebakeColumnMode };
  if (!modes[state.mode]) return fail(`mode ${state.mode}: not tree or 4d`);

  try {
    const stores = await G.getJson("/api/view/stores");
    const probes = await G.getJson("/api/probes");
    if (!(state.store >= 0 && state.store < stores.length))
      return fail(`store ${state.store}: no such store`);
    for (const s of stores) $("store").add(new Option(`${s.name} (${s.width}×${s.height})`, s.index));
    $("store").value = state.store;
    for (const p of probes) $("probe").add(new Option(p, p));
    $("probe").value = state.probe;
    $("mode").value = state.mode;
    $("rotate").value = state.rotate;
    $("rotate-value").textContent = state.rotate;
    $("terms").value = state.terms;
    $("exposure").value = state.exposure;

    const info = stores[state.store];
    const W = info.width, H = info.height;
    $("store-name").textContent = `${info.name}: ${W}×${H}, N = ${info.light_res}, mode ${state.mode}`;
    canvas.width = W;
    canvas.height = H;
    // The cells (albedo, mask), the frame both modes draw into, and its display.
    const cells = await G.getBytes(`/api/view/trees/${state.store}/cells.bin`);
    const ctx = {
      store: state.store, W, H, maxSize: gl.getParameter(gl.MAX_TEXTURE_SIZE),
      cellTex: G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, new Float32Array(cells.buffer)),
      vao: gl.createVertexArray(),
    };
    ctx.frameTex = G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, null);
    ctx.frameFbo = G.framebuffer(gl, ctx.frameTex);
    gl.bindVertexArray(ctx.vao);
    const displayProgram = await G.program(gl, "fullscreen.vert", "display.frag");
    const mode = await modes[state.mode](gl, ctx);

    // uv stores: the lightmapped mesh under an orbit camera (view_mesh.js),
    // unless unticked; the flat frame otherwise. Display only.
    let mesh = null;
    if (info.mesh && window.WavebakeMeshView) {
      try {
        mesh = await window.WavebakeMeshView(gl, ctx, canvas);
      } catch (e) {
        console.log(`3D view: ${e.message}; the lightmap is shown flat`);
      }
    }
    if (mesh) {
      $("view3d-label").hidden = false;
      if (params.get("view") === "flat") $("view3d").checked = false;
      window.wavebakeOrbit = (dyaw, dpitch, zoom) => mesh.turn(dyaw, dpitch, zoom);
    }
    function display() {
      if (mesh && $("view3d").checked) {
        if (canvas.width !== 512) canvas.width = canvas.height = 512;
        mesh.draw(state.exposure);
        document.body.dataset.view3d = "1";
        return;
      }
      if (canvas.width !== W || canvas.height !== H) {
        canvas.width = W;
        canvas.height = H;
      }
      document.body.dataset.view3d = "0";
      gl.bindVertexArray(ctx.vao);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.viewport(0, 0, W, H);
      gl.disable(gl.BLEND);
      gl.useProgram(displayProgram);
      G.bindTextures(gl, [ctx.frameTex]);
      gl.uniform1i(gl.getUniformLocation(displayProgram, "u_frame"), 0);
      gl.uniform1f(gl.getUniformLocation(displayProgram, "u_scale"), Math.pow(2, state.exposure));
      gl.uniform1i(gl.getUniformLocation(displayProgram, "u_height"), H);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    }
    function readFrame() {
      gl.bindFramebuffer(gl.FRAMEBUFFER, ctx.frameFbo);
      const rgba = new Float32Array(W * H * 4);
      gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, rgba);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return rgba;
    }
    window.wavebakeGpuFrame = function () {
      const rgba = readFrame();
      const data = new Float32Array(W * H * 3);
      for (let i = 0; i < W * H; ++i) {
        const masked = rgba[4 * i + 3] === 0;
        for (let c = 0; c < 3; ++c) data[3 * i + c] = masked ? NaN : rgba[4 * i + c];
      }
      return { width: W, height: H, data };
    };
    const device = () => {
      const ext = gl.getExtension("WEBGL_debug_renderer_info");
      return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
    };
    // Frames of the current lighting, each waited for (a one-texel read
    // stalls until the GPU is done), the lighting's transfer excluded.
    window.wavebakeGpuBench = function (frames) {
      const one = new Float32Array(4);
      const sync = () => {
        gl.bindFramebuffer(gl.FRAMEBUFFER, ctx.frameFbo);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, one);
      };
      mode.redraw();
      sync();
      const start = performance.now();
      for (let k = 0; k < frames; ++k) {
        mode.redraw();
        sync();
      }
      const ms = (performance.now() - start) / frames;
      display();
      const frameBytes = 2 * W * H * 16;  // the cells and the frame
      return { mode: mode.name, device: device(), msPerFrame: ms, terms: mode.terms(),
               bytesOnGpu: mode.bytesOnGpu() + frameBytes, work: mode.work(readFrame()) };
    };

    // One lighting request at a time; the latest settings win.
    let pending = false, again = false;
    async function relight() {
      if (pending) return void (again = true);
      pending = true;
      document.body.dataset.gpuReady = "0";
      try {
        const q = new URLSearchParams({ store: state.store, probe: state.probe,
                                        rotate: state.rotate, terms: state.terms });
        const start = performance.now();
        const what = await mode.relight(q);
        display();
        gl.finish();
        const ms = performance.now() - start;
        status.textContent = `${what}; frame ${ms.toFixed(1)} ms (${device()})`;
        document.body.dataset.gpuFrames = String(Number(document.body.dataset.gpuFrames) + 1);
        document.body.dataset.gpuReady = "1";
      } catch (e) {
        fail(String(e.message || e));
      } finally {
        pending = false;
        if (again) {
          again = false;
          relight();
        }
      }
    }

    $("rotate").addEventListener("input", () => {
      state.rotate = Number($("rotate").value);
      $("rotate-value").textContent = state.rotate;
      relight();
    });
    $("terms").addEventListener("change", () => {
      state.terms = Math.max(1, Number($("terms").value) | 0);
      relight();
    });
    $("probe").addEventListener("change", () => {
      state.probe = $("probe").value;
      relight();
    });
    $("view3d").addEventListener("change", display);
    $("exposure").addEventListener("input", () => {
      state.exposure = Number($("exposure").value);
      display();
    });
    const reload = () => {
      const q = new URLSearchParams({ store: $("store").value, probe: state.probe,
                                      rotate: state.rotate, terms: state.terms, mode: $("mode").value });
      location.search = q.toString();
    };
    $("store").addEventListener("change", reload);
    $("mode").addEventListener("change", reload);
    await relight();
  } catch (e) {
    fail(String(e.message || e));
  }
})();
