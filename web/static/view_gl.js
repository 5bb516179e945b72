// WebGL2 and fetch helpers shared by the GPU view's two modes (view.js,
// view_tree.js, view_4d.js).
"use strict";

window.WavebakeGL = (function () {
  async function getJson(url) {
    const r = await fetch(url, { cache: "no-store" });
    const body = await r.json();
    if (!r.ok) throw new Error(body.error || `${url}: HTTP ${r.status}`);
    return body;
  }
  async function getBytes(url) {
    const r = await fetch(url, { cache: "no-store" });
    if (!r.ok) {
      let message = `${url}: HTTP ${r.status}`;
      try { message = (await r.json()).error || message; } catch (e) { /* not JSON */ }
      throw new Error(message);
    }
    return { buffer: await r.arrayBuffer(), headers: r.headers };
  }
  async function getText(url) {
    const r = await fetch(url);
    if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
    return r.text();
  }

  function compile(gl, type, source, name) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS))
      throw new Error(`${name}: ${gl.getShaderInfoLog(s)}`);
    return s;
  }
  // The program of two shader files of /static/.
  async function program(gl, vertName, fragName) {
    const [vs, fs] = await Promise.all([vertName, fragName].map((f) => getText("/static/" + f)));
    const p = gl.createProgram();
    gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, vs, vertName));
    gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, fs, fragName));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS))
      throw new Error(`${fragName}: ${gl.getProgramInfoLog(p)}`);
    return p;
  }
  // A nearest-sampled texture of `width` texels a row and `rows` rows
  // (at least one) from `data` (null: uninitialized).
  function texture(gl, internal, format, type, width, rows, data) {
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
  // `data` padded with zeros to whole rows of `row` texels of `channels`.
  function padded(Type, data, row, channels) {
    const rows = Math.max(1, Math.ceil(data.length / channels / row));
    const out = new Type(rows * row * channels);
    out.set(data);
    return { data: out, rows };
  }
  // A framebuffer drawing into texture t (checked complete).
  function framebuffer(gl, t) {
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, t, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
      throw new Error("a float framebuffer is not renderable here");
    return fbo;
  }
  function bindTextures(gl, textures) {
    textures.forEach((t, i) => {
      gl.activeTexture(gl.TEXTURE0 + i);
      gl.bindTexture(gl.TEXTURE_2D, t);
    });
  }
  return { getJson, getBytes, getText, program, texture, padded, framebuffer, bindTextures };
})();
