// mode=tree of the GPU view (web/views/gpu_view.h): the store's wavelet-tree
// textures (header.json documents them) uploaded once; per probe, rotation
// and term count the server sends the environment trees (a few KB) and
// wavelet_tree.frag computes B per texel by walking both trees in parallel
// (Boulton §4.5, Eq. 3) into the common float frame (view.js).
"use strict";

window.WavebakeTreeMode = async function (gl, ctx) {
  const G = window.WavebakeGL;
  const base = `/api/view/trees/${ctx.store}/`;
  const header = await G.getJson(base + "header.json");
  if (header.format !== "wavebake-wavelet-tree/2") throw new Error("unknown tree format");
  const row = header.line.width;
  if (header.blocks.width !== row) throw new Error("blocks and line rows differ");
  if (row > ctx.maxSize || header.line.height > ctx.maxSize || header.blocks.height > ctx.maxSize)
    throw new Error(`the trees need ${row}×${header.line.height} texels; this GPU allows ${ctx.maxSize}`);
  if (header.levels > 8) throw new Error("more than 8 levels");
  const [line, blocks] = await Promise.all(
    [header.line.file, header.blocks.file].map((f) => G.getBytes(base + f)));
  const prog = await G.program(gl, "fullscreen.vert", "wavelet_tree.frag");
  const lineTex = G.texture(gl, gl.RGBA8UI, gl.RGBA_INTEGER, gl.UNSIGNED_BYTE, row,
                            header.line.height, new Uint8Array(line.buffer));
  // An empty export (no sampled cell) still binds a 1-texel block texture.
  const blockTex = G.texture(gl, gl.RG32UI, gl.RG_INTEGER, gl.UNSIGNED_INT, row,
                             Math.max(1, header.blocks.height),
                             header.blocks.height ? new Uint32Array(blocks.buffer)
                                                  : new Uint32Array(2 * row));
  let envTex = null, envBytes = 0, env = null;
  const u = (name) => gl.getUniformLocation(prog, name);
  gl.useProgram(prog);
  gl.uniform1i(u("u_line"), 0);
  gl.uniform1i(u("u_blocks"), 1);
  gl.uniform1i(u("u_cells"), 2);
  gl.uniform1i(u("u_env"), 3);
  gl.uniform1i(u("u_row"), row);
  gl.uniform1i(u("u_levels"), header.levels);
  const perLevel = (a) => Array.from({ length: 8 }, (_, l) => (l < a.length ? a[l] : 0));
  gl.uniform1iv(u("u_bits[0]"), perLevel(header.code_bits));
  gl.uniform1iv(u("u_units[0]"), perLevel(header.record_units));
  gl.uniform1i(u("u_step_bias"), header.step_bias);

  function upload(e) {
    const p = G.padded(Float32Array, e.records, row, 4);
    if (envTex) gl.deleteTexture(envTex);
    envTex = G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, row, p.rows, p.data);
    envBytes = p.data.byteLength;
    gl.useProgram(prog);
    gl.uniform1iv(u("u_env_offset[0]"), e.faces.map((f) => f.offset));
    gl.uniform1iv(u("u_env_count[0]"), e.faces.map((f) => f.count));
    gl.uniform3fv(u("u_env_scaling[0]"), e.faces.flatMap((f) => f.scaling));
  }
  function draw() {
    gl.bindFramebuffer(gl.FRAMEBUFFER, ctx.frameFbo);
    gl.viewport(0, 0, ctx.W, ctx.H);
    gl.disable(gl.BLEND);
    gl.useProgram(prog);
    G.bindTextures(gl, [lineTex, blockTex, ctx.cellTex, envTex]);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }
  return {
    name: "tree",
    async relight(q) {
      env = await G.getJson(`/api/view/env?${q}`);
      upload(env);
      draw();
      return `${env.terms} wavelet lights; environment trees ${(envBytes / 1024).toFixed(1)} KB`;
    },
    redraw: draw,
    terms: () => (env ? env.terms : 0),
    // The line, block and environment textures; the common frame and cells are view.js's.
    bytesOnGpu: () => line.buffer.byteLength + blocks.buffer.byteLength + envBytes,
    // Work per sampled cell: the transfer records wavelet_tree.frag read (alpha − 1).
    work(rgba) {
      let records = 0, cells = 0;
      for (let i = 3; i < rgba.length; i += 4)
        if (rgba[i] > 0) { records += rgba[i] - 1; ++cells; }
      return { unit: "records read", perPixel: cells ? records / cells : 0, passes: 1 };
    },
  };
};
