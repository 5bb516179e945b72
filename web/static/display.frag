#version 300 es
// The relit float frame (linear RGB, row 0 = the grid's top row, alpha 0 on
// masked cells) shown on the canvas: × 2^exposure, clamped, sRGB-encoded;
// masked cells dark grey as in the server's relight view.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_frame;
uniform float u_scale;  // 2^exposure
uniform int u_height;   // rows of the frame

out vec4 o_color;

vec3 srgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 v = texelFetch(u_frame, ivec2(p.x, u_height - 1 - p.y), 0);
  if (v.a == 0.0) {
    o_color = vec4(srgb(vec3(0.02, 0.02, 0.025)), 1.0);
    return;
  }
  o_color = vec4(srgb(clamp(v.rgb * u_scale, 0.0, 1.0)), 1.0);
}
