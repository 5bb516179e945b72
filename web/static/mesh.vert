#version 300 es
// The GPU view's 3D display of a uv store (view_mesh.js): the baked meshes
// under an orbit camera, each vertex carrying its lightmap position in texel
// units of the relit W×H frame.
precision highp float;

in vec3 a_position;
in vec2 a_texel;  // x right, y down from the grid's row 0
uniform mat4 u_mvp;

out vec2 v_texel;

void main() {
  v_texel = a_texel;
  gl_Position = u_mvp * vec4(a_position, 1.0);
}
