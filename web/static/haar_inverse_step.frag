#version 300 es
// One single-step inverse column transform S'_{l→l+1} of Eq. 8 (4D paper
// §4.5): step u_step of the 2D non-standard orthonormal Haar transform
// (core/wavelets/haar2d.h) undone on the top-left (W>>s)×(H>>s) block of
// the column buffer, every other texel copied. Each 2×2 cell comes from
// LL, HL, LH, HH of the block's quarters with the same operations, in the
// same order, as the CPU relighter's: ½((LL ± HL) ± (LH ± HH)). Below the
// matrix's largest depth both sides of the block are ≥ 2.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D u_src;  // W×H RGBA32F, the buffer at depth u_step + 1
uniform int u_step;
uniform ivec2 u_size;

out vec4 o_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int bw = u_size.x >> u_step, bh = u_size.y >> u_step;
  if (p.x >= bw || p.y >= bh) {
    o_color = texelFetch(u_src, p, 0);
    return;
  }
  int hw = bw / 2, hh = bh / 2, i = p.x >> 1, j = p.y >> 1;
  vec3 ll = texelFetch(u_src, ivec2(i, j), 0).rgb;
  vec3 hl = texelFetch(u_src, ivec2(hw + i, j), 0).rgb;
  vec3 lh = texelFetch(u_src, ivec2(i, hh + j), 0).rgb;
  vec3 hd = texelFetch(u_src, ivec2(hw + i, hh + j), 0).rgb;
  bool odd_x = (p.x & 1) == 1, odd_y = (p.y & 1) == 1;
  vec3 a = odd_x ? ll - hl : ll + hl;
  vec3 b = odd_x ? lh - hd : lh + hd;
  o_color = vec4(0.5 * (odd_y ? a - b : a + b), 0.0);
}
