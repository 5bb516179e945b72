// mode=4d of the GPU view (web/views/gpu_view.h): the 4D store itself relit on
// the GPU, Eq. 8 of the 4D paper (§4.5, Fig. 6). The store's CSC arrays
// (meta.json documents them) are uploaded once. Per probe, rotation and
// term count the server sends the kept lights (column, RGB weight); the
// page sorts them by their column's depth, deepest first, and for each
// depth group scatters every kept coefficient w_i·C_ik into a W×H float
// buffer with additive blending (column_scatter.vert: WebGL2 has no
// compute shaders), then inverts one Haar column step
// (haar_inverse_step.frag) before the next, shallower group joins; the
// last pass multiplies by the albedo (column_compose.frag).
"use strict";

window.WavebakeColumnMode = async function (gl, ctx) {
  const G = window.WavebakeGL;
  if (!gl.getExtension("EXT_float_blend"))
    throw new Error("EXT_float_blend is missing: no additive blending into float targets");
  // `wavebake view`'s routes, or the job page's (ctx.columnsBase, ctx.lightsUrl).
  const base = ctx.columnsBase || `/api/view/columns/${ctx.store}/`;
  const lightsUrl = ctx.lightsUrl || ((q) => `/api/view/lights?${q}`);
  const meta = await G.getJson(base + "meta.json");
  if (meta.format !== "wavebake-columns/1") throw new Error("unknown columns format");
  if (meta.column_filter !== "haar") throw new Error(`column filter ${meta.column_filter}: not Haar`);
  if (meta.width !== ctx.W || meta.height !== ctx.H) throw new Error("columns and cells differ");
  const row = meta.entries.width;
  if (row > ctx.maxSize || meta.entries.height > ctx.maxSize)
    throw new Error(`the store needs ${row}×${meta.entries.height} texels; this GPU allows ${ctx.maxSize}`);
  const [entries, indptrBytes, depthBytes] = await Promise.all(
    [meta.entries.file, meta.indptr.file, meta.depth.file].map((f) => G.getBytes(base + f)));
  const indptr = new Uint32Array(indptrBytes.buffer), depth = new Uint8Array(depthBytes.buffer);
  if (indptr.length !== meta.columns + 1 || depth.length !== meta.columns)
    throw new Error("indptr or depth: not the columns' length");
  const entryTex = G.texture(gl, gl.RG32UI, gl.RG_INTEGER, gl.UNSIGNED_INT, row, meta.entries.height,
                             new Uint32Array(entries.buffer));
  const [scatter, inverse, compose] = await Promise.all([
    G.program(gl, "column_scatter.vert", "column_scatter.frag"),
    G.program(gl, "fullscreen.vert", "haar_inverse_step.frag"),
    G.program(gl, "fullscreen.vert", "column_compose.frag")]);
  // Ping-pong column buffers.
  const buffers = [0, 1].map(() => G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, ctx.W, ctx.H, null));
  const fbos = buffers.map((t) => G.framebuffer(gl, t));
  const u = (p, name) => gl.getUniformLocation(p, name);
  gl.useProgram(scatter);
  gl.uniform1i(u(scatter, "u_entries"), 0);
  gl.uniform1i(u(scatter, "u_light_at"), 1);
  gl.uniform1i(u(scatter, "u_light_w"), 2);
  gl.uniform1i(u(scatter, "u_row"), row);
  gl.uniform2i(u(scatter, "u_size"), ctx.W, ctx.H);
  gl.useProgram(inverse);
  gl.uniform1i(u(inverse, "u_src"), 0);
  gl.uniform2i(u(inverse, "u_size"), ctx.W, ctx.H);
  gl.useProgram(compose);
  gl.uniform1i(u(compose, "u_buffer"), 0);
  gl.uniform1i(u(compose, "u_cells"), 1);

  let atTex = null, wTex = null, lightBytes = 0;
  let groups = [], deepest = -1, coefficients = 0, terms = 0;

  // The lights sorted by depth, deepest first (the order of Eq. 8), those
  // with no kept coefficient dropped; per depth group its lights and points.
  function plan(buffer) {
    const view = new DataView(buffer);
    const count = buffer.byteLength / 16;
    const lights = [];
    for (let k = 0; k < count; ++k) {
      const column = view.getUint32(16 * k, true);
      if (column >= meta.columns) throw new Error(`lights: column ${column} outside the store`);
      lights.push({ column, d: depth[column], w: [1, 2, 3].map((c) => view.getFloat32(16 * k + 4 * c, true)) });
    }
    terms = count;
    const order = lights.map((l, k) => k).sort((a, b) => lights[b].d - lights[a].d || a - b);
    const at = [], w = [];
    groups = [];
    deepest = lights.length ? Math.max(...lights.map((l) => l.d)) : -1;
    coefficients = 0;
    let group = null;
    for (const k of order) {
      const l = lights[k], n = indptr[l.column + 1] - indptr[l.column];
      if (n === 0) continue;
      if (!group || group.d !== l.d) groups.push(group = { d: l.d, first: at.length / 2, count: 0, points: 0 });
      at.push(group.points, indptr[l.column]);
      w.push(...l.w, 0);
      group.count += 1;
      group.points += n;
      coefficients += n;
    }
    const pa = G.padded(Uint32Array, at, row, 2), pw = G.padded(Float32Array, w, row, 4);
    if (atTex) gl.deleteTexture(atTex);
    if (wTex) gl.deleteTexture(wTex);
    atTex = G.texture(gl, gl.RG32UI, gl.RG_INTEGER, gl.UNSIGNED_INT, row, pa.rows, pa.data);
    wTex = G.texture(gl, gl.RGBA32F, gl.RGBA, gl.FLOAT, row, pw.rows, pw.data);
    lightBytes = pa.data.byteLength + pw.data.byteLength;
  }

  function draw() {
    const vao = ctx.vao;
    gl.bindVertexArray(vao);
    gl.viewport(0, 0, ctx.W, ctx.H);
    let cur = 0;
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbos[cur]);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT);
    for (let d = deepest; d >= 0; --d) {
      const g = groups.find((x) => x.d === d);
      if (g) {
        gl.bindFramebuffer(gl.FRAMEBUFFER, fbos[cur]);
        gl.enable(gl.BLEND);
        gl.blendEquation(gl.FUNC_ADD);
        gl.blendFunc(gl.ONE, gl.ONE);
        gl.useProgram(scatter);
        gl.uniform1i(u(scatter, "u_first"), g.first);
        gl.uniform1i(u(scatter, "u_count"), g.count);
        G.bindTextures(gl, [entryTex, atTex, wTex]);
        gl.drawArrays(gl.POINTS, 0, g.points);
        gl.disable(gl.BLEND);
      }
      if (d === 0) break;
      gl.bindFramebuffer(gl.FRAMEBUFFER, fbos[1 - cur]);
      gl.useProgram(inverse);
      gl.uniform1i(u(inverse, "u_step"), d - 1);
      G.bindTextures(gl, [buffers[cur]]);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      cur = 1 - cur;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, ctx.frameFbo);
    gl.useProgram(compose);
    G.bindTextures(gl, [buffers[cur], ctx.cellTex]);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  return {
    name: "4d",
    async relight(q) {
      const r = await G.getBytes(lightsUrl(q));
      plan(r.buffer);
      draw();
      return `${terms} wavelet lights; ${coefficients} coefficients scattered in ` +
             `${groups.length} depth groups, ${Math.max(deepest, 0)} inverse steps`;
    },
    redraw: draw,
    terms: () => terms,
    // The entries texture, the two column buffers and the light list; the
    // common frame and cells are view.js's.
    bytesOnGpu: () => entries.buffer.byteLength + 2 * ctx.W * ctx.H * 16 + lightBytes,
    // Work per cell: the coefficients scattered (one point each) over the
    // grid, and the full-screen passes (one per inverse step, and the compose).
    work: () => ({ unit: "coefficients scattered", perPixel: coefficients / (ctx.W * ctx.H),
                   passes: Math.max(deepest, 0) + 1 }),
  };
};
