#version 300 es
// The 4D mode's last pass: the column buffer, now in the pixel domain
// (Σ_i w_i S'(C_i) per cell), times the cell's albedo (factored out of T,
// DESIGN.md §1) into the frame the page shows and reads back: alpha 1 on
// sampled cells, 0 on masked ones.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_buffer;  // W×H RGBA32F
uniform sampler2D u_cells;   // W×H: albedo RGB, A 0 masked, > 0 sampled

out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 cell = texelFetch(u_cells, p, 0);
  if (cell.a == 0.0) {
    o_color = vec4(0.0);
    return;
  }
  o_color = vec4(texelFetch(u_buffer, p, 0).rgb * cell.rgb, 1.0);
}
