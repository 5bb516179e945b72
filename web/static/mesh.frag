#version 300 es
// The relit lightmap on the mesh (mesh.vert): the frame's texel under the
// fragment, × 2^exposure, sRGB. A fragment at a chart's border can land on
// a texel no triangle covers (alpha 0): the nearest covered texel within 2
// stands in for it, as the glTF output's dilated gutters do.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D u_frame;  // W×H RGBA32F, alpha 0 on uncovered texels
uniform ivec2 u_size;
uniform float u_scale;

in vec2 v_texel;
out vec4 o_color;

vec3 srgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  ivec2 t = clamp(ivec2(floor(v_texel)), ivec2(0), u_size - 1);
  vec4 v = texelFetch(u_frame, t, 0);
  vec4 near = vec4(0.02, 0.02, 0.025, 1.0);  // nothing covered nearby: the background
  int best = 100;
  for (int dy = -2; dy <= 2 && v.a == 0.0; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      ivec2 q = t + ivec2(dx, dy);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_size))) continue;
      vec4 w = texelFetch(u_frame, q, 0);
      int d = dx * dx + dy * dy;
      if (w.a > 0.0 && d < best) {
        best = d;
        near = w;
      }
    }
  }
  if (v.a == 0.0) v = near;
  o_color = vec4(srgb(clamp(v.rgb * u_scale, 0.0, 1.0)), 1.0);
}
