#version 300 es
// Eq. 8's sparse add (4D paper §4.5) on a GPU without compute shaders: one
// point per kept coefficient of a depth group's lights, drawn at the
// coefficient's position of the W×H column buffer, carrying w_i·C_ik;
// additive float blending (EXT_float_blend) sums them where they land.
// Point v of the draw belongs to the group's last light whose first point
// is ≤ v (a binary search over the frame's light list, lights with no
// coefficient left out by the page).
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp usampler2D;

uniform usampler2D u_entries;   // RG32UI: position y·W + x, float bits of the value
uniform usampler2D u_light_at;  // RG32UI per light: first point in its group, first entry
uniform sampler2D u_light_w;    // RGBA32F per light: weight RGB
uniform int u_first;            // the group's first light in the list
uniform int u_count;            // its lights (≥ 1)
uniform int u_row;              // texels a row of the three textures
uniform ivec2 u_size;           // W, H

flat out vec3 v_value;

ivec2 at(int k) { return ivec2(k % u_row, k / u_row); }

void main() {
  int v = gl_VertexID;
  int lo = u_first, hi = u_first + u_count - 1;
  while (lo < hi) {
    int mid = (lo + hi + 1) >> 1;
    if (int(texelFetch(u_light_at, at(mid), 0).x) <= v)
      lo = mid;
    else
      hi = mid - 1;
  }
  uvec2 light = texelFetch(u_light_at, at(lo), 0).xy;
  int k = int(light.y) + (v - int(light.x));
  uvec2 e = texelFetch(u_entries, at(k), 0).xy;
  v_value = texelFetch(u_light_w, at(lo), 0).rgb * uintBitsToFloat(e.y);
  int p = int(e.x);
  vec2 cell = vec2(float(p % u_size.x), float(p / u_size.x)) + 0.5;
  gl_Position = vec4(cell / vec2(u_size) * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
