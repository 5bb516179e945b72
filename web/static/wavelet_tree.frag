#version 300 es
// B per texel of the sample grid from wavelet-tree textures (Boulton §4.5,
// Eq. 3): for each cube face, the transfer tree of the texel (exported by
// `wavebake export --format wavelet-tree`, its layout in header.json) and
// the environment tree of the face (runtime/gpu/env_trees.h, sent by the server
// per probe, rotation and term count) are walked in parallel, depth first;
// only nodes present in both trees are visited. When one tree has children
// where the other has none, its jump record skips the whole branch: the
// sibling rule of §4.4 (four children go together) makes both walks land on
// the same node. I = S_A·S_B + Σ_{i ∈ A∩B} C_A^i · C_B^i per channel, then
// × albedo. Masked cells come out with alpha 0, sampled ones with alpha
// 1 + the nodes visited (the per-pixel work the page reports).
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp usampler2D;

uniform usampler2D u_line;    // transfer records, RGBA8UI or RGBA16UI
uniform usampler2D u_blocks;  // per cell·6 + face: offset, texels, scaling bits, step bits
uniform sampler2D u_cells;    // W×H: albedo RGB, A 1 sampled / 0 masked
uniform sampler2D u_env;      // environment records, 3 RGBA32F texels each
uniform int u_width;          // grid width
uniform int u_row;            // texels a row of u_line, u_blocks and u_env
uniform int u_bits;           // 8 or 16: jump offset = R + (G << bits)
uniform float u_bias;         // code of a zero coefficient
uniform int u_env_offset[6];  // first record of each face's environment tree
uniform int u_env_count[6];   // its records (0: no wavelet node)
uniform vec3 u_env_scaling[6];

out vec4 o_color;

// Nodes of the largest tree (N = 256: (N² − 1)/3) bound every walk.
const int kMaxSteps = 21845;

uvec4 lineAt(int k) { return texelFetch(u_line, ivec2(k % u_row, k / u_row), 0); }
vec4 envAt(int k) { return texelFetch(u_env, ivec2(k % u_row, k / u_row), 0); }

vec3 faceProduct(int face, uvec4 block, inout int visited) {
  vec3 sum = uintBitsToFloat(block.z) * u_env_scaling[face];
  if (block.y == 0u || u_env_count[face] == 0) return sum;
  float step = uintBitsToFloat(block.w);
  int a = int(block.x);       // transfer record
  int b = u_env_offset[face]; // environment record
  int level = 0;
  for (int it = 0; it < kMaxSteps; ++it) {
    uvec4 ta = lineAt(a);
    vec3 ca = (vec3(ta.rgb) - u_bias) * step;
    vec4 e0 = envAt(3 * b);
    vec4 e1 = envAt(3 * b + 1);
    vec4 e2 = envAt(3 * b + 2);
    sum += ca.x * e0.rgb + ca.y * e1.rgb + ca.z * e2.rgb;
    ++visited;
    int na = int(ta.a) - 1;          // level of the next node, −1: end
    int nb = int(e0.a + 0.5) - 1;
    bool childA = na > level;
    bool childB = nb > level;
    if (childA && childB) {          // both descend: skip both jump records
      a += 2;
      b += 2;
      level += 1;
      continue;
    }
    if (childA) {                    // the environment has no children here
      uvec4 j = lineAt(a + 1);
      a += int(j.r) + (int(j.g) << u_bits);
      b += 1;
      level = nb;
    } else if (childB) {             // the transfer tree has none
      vec4 j = envAt(3 * (b + 1));
      b += int(j.r + 0.5);
      a += 1;
      level = na;
    } else {
      a += 1;
      b += 1;
      level = na;
    }
    if (level < 0) break;
  }
  return sum;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 cell = texelFetch(u_cells, p, 0);
  if (cell.a == 0.0) {
    o_color = vec4(0.0);
    return;
  }
  int c = p.y * u_width + p.x;
  vec3 sum = vec3(0.0);
  int visited = 0;
  for (int face = 0; face < 6; ++face) {
    int k = c * 6 + face;
    sum += faceProduct(face, texelFetch(u_blocks, ivec2(k % u_row, k / u_row), 0), visited);
  }
  o_color = vec4(sum * cell.rgb, 1.0 + float(visited));
}
