// The GPU view's 3D display of a uv store: the baked meshes (from
// /api/view/mesh/I, the scene reloaded by the server) textured with the
// relit lightmap frame both modes draw, under an orbit camera (drag to turn,
// wheel to zoom). Display only: turning the camera redraws this pass, no
// relighting and no request.
"use strict";

window.WavebakeMeshView = async function (gl, ctx, canvas) {
  const G = window.WavebakeGL;
  const r = await G.getBytes(`/api/view/mesh/${ctx.store}`);
  const head = new Uint32Array(r.buffer, 0, 2), V = head[0], I = head[1];
  const positions = new Float32Array(r.buffer, 8, 3 * V);
  const texels = new Float32Array(r.buffer, 8 + 12 * V, 2 * V);
  const indices = new Uint32Array(r.buffer, 8 + 20 * V, I);
  const prog = await G.program(gl, "mesh.vert", "mesh.frag");
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  const attribute = (name, data, size) => {
    const b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    const at = gl.getAttribLocation(prog, name);
    gl.enableVertexAttribArray(at);
    gl.vertexAttribPointer(at, size, gl.FLOAT, false, 0, 0);
  };
  attribute("a_position", positions, 3);
  attribute("a_texel", texels, 2);
  const ib = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
  gl.bindVertexArray(ctx.vao);

  // The orbit: about the bounding box's centre, from outside its sphere.
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < V; ++v)
    for (let k = 0; k < 3; ++k) {
      lo[k] = Math.min(lo[k], positions[3 * v + k]);
      hi[k] = Math.max(hi[k], positions[3 * v + k]);
    }
  const centre = lo.map((l, k) => (l + hi[k]) / 2);
  const radius = Math.hypot(...hi.map((h, k) => h - lo[k])) / 2 || 1;
  const orbit = { yaw: 0.6, pitch: 0.35, distance: 2.8 * radius };

  const sub = (a, b) => a.map((x, k) => x - b[k]);
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  function mvp(aspect) {
    const e = [centre[0] + orbit.distance * Math.cos(orbit.pitch) * Math.sin(orbit.yaw),
               centre[1] + orbit.distance * Math.sin(orbit.pitch),
               centre[2] + orbit.distance * Math.cos(orbit.pitch) * Math.cos(orbit.yaw)];
    const f = norm(sub(centre, e)), s = norm(cross(f, [0, 1, 0])), u = cross(s, f);
    const near = orbit.distance * 0.05, far = orbit.distance * 4, t = 1 / Math.tan(Math.PI / 9);
    // Column-major projection × view.
    const P = [t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (far + near) / (near - far), -1,
               0, 0, 2 * far * near / (near - far), 0];
    const Vw = [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                -dot(s, e), -dot(u, e), dot(f, e), 1];
    const M = new Float32Array(16);
    for (let c = 0; c < 4; ++c)
      for (let r = 0; r < 4; ++r) {
        let x = 0;
        for (let k = 0; k < 4; ++k) x += P[4 * k + r] * Vw[4 * c + k];
        M[4 * c + r] = x;
      }
    return M;
  }

  let exposure = 0;
  function draw(e) {
    if (e !== undefined) exposure = e;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.disable(gl.BLEND);
    gl.enable(gl.DEPTH_TEST);
    gl.clearColor(0.106, 0.106, 0.122, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.useProgram(prog);
    gl.bindVertexArray(vao);
    G.bindTextures(gl, [ctx.frameTex]);
    gl.uniform1i(gl.getUniformLocation(prog, "u_frame"), 0);
    gl.uniform2i(gl.getUniformLocation(prog, "u_size"), ctx.W, ctx.H);
    gl.uniform1f(gl.getUniformLocation(prog, "u_scale"), Math.pow(2, exposure));
    gl.uniformMatrix4fv(gl.getUniformLocation(prog, "u_mvp"), false, mvp(canvas.width / canvas.height));
    gl.drawElements(gl.TRIANGLES, I, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(ctx.vao);
    gl.disable(gl.DEPTH_TEST);
  }
  // Turn (radians) and zoom (a factor) the camera, then redraw.
  function turn(dyaw, dpitch, zoom = 1) {
    orbit.yaw += dyaw;
    orbit.pitch = Math.max(-1.5, Math.min(1.5, orbit.pitch + dpitch));
    orbit.distance = Math.max(radius * 0.5, Math.min(radius * 20, orbit.distance * zoom));
    draw();
  }
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    turn(-(e.clientX - drag[0]) * 0.01, (e.clientY - drag[1]) * 0.01);
    drag = [e.clientX, e.clientY];
  });
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); turn(0, 0, Math.exp(e.deltaY * 0.001)); },
                          { passive: false });
  return { draw, turn, triangles: I / 3 };
};
