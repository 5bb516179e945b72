// The GPU relight view (web/gpu_view.h): a store's wavelet-tree textures
// (header.json documents them) uploaded once; per probe, rotation and term
// count the server sends the environment trees (a few KB) and the fragment
// shader wavelet_tree.frag computes B per texel (Boulton §4.5, Eq. 3) into
// a float target; display.frag shows it. No pixels cross the network.
//
// Testability contract: once a frame is drawn, document.body.dataset.gpuReady
// is "1" and window.wavebakeGpuFrame() returns {width, height, data}: data a
// Float32Array of linear RGB, row 0 at the top, NaN where masked — the shape
// of the Python module's wavebake.relight(Store, probe, terms, rotate).
"use strict";

(async function () {
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
  if (state.mode !== "tree") return fail(`mode ${state.mode}: only mode=tree is available`);

  const getJson = async (url) => {
    const r = await fetch(url);
    const body = await r.json();
    if (!r.ok) throw new Error(body.error || `${url}: HTTP ${r.status}`);
    return body;
  };
  const getText = async (url) => (await fetch(url)).text();
  const getBytes = async (url) => {
    const r = await fetch(url);
    if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
    return r.arrayBuffer();
  };

  function compile(type, source, name) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS))
      throw new Error(`${name}: ${gl.getShaderInfoLog(s)}`);
    return s;
  }
  function program(vs, fs, name) {
    const p = gl.createProgram();
    gl.attachShader(p, vs);
    gl.attachShader(p, fs);
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS))
      throw new Error(`${name}: ${gl.getProgramInfoLog(p)}`);
    return p;
  }
  // A texture of `width` texels a row holding `texels` RGBA texels of `data`
  // (padded to whole rows, at least one).
  function texture(internal, format, type, width, rows, data) {
    const t = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, t);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, internal, width, Math.max(rows, 1), 0, format, type, data);
    return t;
  }

  try {
    const stores = await getJson("/api/view/stores");
    const probes = await getJson("/api/probes");
    if (!(state.store >= 0 && state.store < stores.length))
      return fail(`store ${state.store}: no such store`);
    for (const s of stores) $("store").add(new Option(`${s.name} (${s.width}×${s.height})`, s.index));
    $("store").value = state.store;
    for (const p of probes) $("probe").add(new Option(p, p));
    $("probe").value = state.probe;
    $("rotate").value = state.rotate;
    $("rotate-value").textContent = state.rotate;
    $("terms").value = state.terms;
    $("exposure").value = state.exposure;

    const base = `/api/view/trees/${state.store}/`;
    const header = await getJson(base + "header.json");
    if (header.format !== "wavebake-wavelet-tree/1") return fail("unknown tree format");
    const [line, blocks, cells] = await Promise.all(
      [header.line.file, header.blocks.file, header.cells.file].map((f) => getBytes(base + f)));
    const W = header.width, H = header.height, row = header.line.width;
    if (header.blocks.width !== row) return fail("blocks and line rows differ");
    const maxSize = gl.getParameter(gl.MAX_TEXTURE_SIZE);
    if (row > maxSize || header.line.height > maxSize || header.blocks.height > maxSize)
      return fail(`the trees need ${row}×${header.line.height} texels; this GPU allows ${maxSize}`);
    $("store-name").textContent = `${stores[state.store].name}: ${W}×${H}, N = ${header.light_res}`;
    canvas.width = W;
    canvas.height = H;

    const [vsText, treeText, displayText] = await Promise.all(
      ["fullscreen.vert", "wavelet_tree.frag", "display.frag"].map((f) => getText("/static/" + f)));
    const vs = compile(gl.VERTEX_SHADER, vsText, "fullscreen.vert");
    const treeProgram = program(vs, compile(gl.FRAGMENT_SHADER, treeText, "wavelet_tree.frag"),
                                "wavelet_tree");
    const displayProgram = program(vs, compile(gl.FRAGMENT_SHADER, displayText, "display.frag"),
                                   "display");

    const bits8 = header.bits === 8;
    const lineTex = texture(bits8 ? gl.RGBA8UI : gl.RGBA16UI, gl.RGBA_INTEGER,
                            bits8 ? gl.UNSIGNED_BYTE : gl.UNSIGNED_SHORT, row, header.line.height,
                            bits8 ? new Uint8Array(line) : new Uint16Array(line));
    const blockTex = texture(gl.RGBA32UI, gl.RGBA_INTEGER, gl.UNSIGNED_INT, row,
                             header.blocks.height, new Uint32Array(blocks));
    const cellTex = texture(gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, new Float32Array(cells));
    let envTex = null;

    // The float target the tree shader draws into: W×H, one texel a cell.
    const frameTex = texture(gl.RGBA32F, gl.RGBA, gl.FLOAT, W, H, null);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, frameTex, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
      return fail("a float framebuffer is not renderable here");
    const vao = gl.createVertexArray();

    const u = (p, name) => gl.getUniformLocation(p, name);
    gl.useProgram(treeProgram);
    gl.uniform1i(u(treeProgram, "u_line"), 0);
    gl.uniform1i(u(treeProgram, "u_blocks"), 1);
    gl.uniform1i(u(treeProgram, "u_cells"), 2);
    gl.uniform1i(u(treeProgram, "u_env"), 3);
    gl.uniform1i(u(treeProgram, "u_width"), W);
    gl.uniform1i(u(treeProgram, "u_row"), row);
    gl.uniform1i(u(treeProgram, "u_bits"), header.bits);
    gl.uniform1f(u(treeProgram, "u_bias"), header.bias);

    function uploadEnv(env) {
      const texels = env.records.length / 4;
      const rows = Math.max(1, Math.ceil(texels / row));
      const data = new Float32Array(rows * row * 4);
      data.set(env.records);
      if (envTex) gl.deleteTexture(envTex);
      envTex = texture(gl.RGBA32F, gl.RGBA, gl.FLOAT, row, rows, data);
      gl.useProgram(treeProgram);
      gl.uniform1iv(u(treeProgram, "u_env_offset[0]"), env.faces.map((f) => f.offset));
      gl.uniform1iv(u(treeProgram, "u_env_count[0]"), env.faces.map((f) => f.count));
      gl.uniform3fv(u(treeProgram, "u_env_scaling[0]"), env.faces.flatMap((f) => f.scaling));
    }

    function drawFrame() {
      gl.bindVertexArray(vao);
      gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
      gl.viewport(0, 0, W, H);
      gl.useProgram(treeProgram);
      [lineTex, blockTex, cellTex, envTex].forEach((t, i) => {
        gl.activeTexture(gl.TEXTURE0 + i);
        gl.bindTexture(gl.TEXTURE_2D, t);
      });
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      display();
    }
    function display() {
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      gl.viewport(0, 0, W, H);
      gl.useProgram(displayProgram);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, frameTex);
      gl.uniform1i(u(displayProgram, "u_frame"), 0);
      gl.uniform1f(u(displayProgram, "u_scale"), Math.pow(2, state.exposure));
      gl.uniform1i(u(displayProgram, "u_height"), H);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    }

    window.wavebakeGpuFrame = function () {
      gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
      const rgba = new Float32Array(W * H * 4);
      gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, rgba);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      const data = new Float32Array(W * H * 3);
      for (let i = 0; i < W * H; ++i) {
        const masked = rgba[4 * i + 3] === 0;
        for (let c = 0; c < 3; ++c) data[3 * i + c] = masked ? NaN : rgba[4 * i + c];
      }
      return { width: W, height: H, data };
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
        const env = await getJson(`/api/view/env?${q}`);
        uploadEnv(env);
        drawFrame();
        gl.finish();
        const ms = performance.now() - start;
        status.textContent = `${env.terms} wavelet lights; environment trees ` +
            `${(env.records.length * 4 / 1024).toFixed(1)} KB; frame ${ms.toFixed(1)} ms ` +
            `(${gl.getParameter(gl.RENDERER)})`;
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
    $("exposure").addEventListener("input", () => {
      state.exposure = Number($("exposure").value);
      display();
    });
    $("store").addEventListener("change", () => {
      const q = new URLSearchParams({ store: $("store").value, probe: state.probe,
                                      rotate: state.rotate, terms: state.terms, mode: "tree" });
      location.search = q.toString();
    });
    await relight();
  } catch (e) {
    fail(String(e.message || e));
  }
})();
