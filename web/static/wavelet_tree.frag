#version 300 es
// B per texel of the sample grid from wavelet-tree textures (Boulton §4.5,
// Eq. 3): for each cube face, the transfer tree of the texel (exported by
// `wavebake export --format wavelet-tree`, its layout in header.json) and
// the environment tree of the face (runtime/gpu/env_trees.h, sent by the server
// per probe, rotation and term count) are walked in parallel, depth first.
// Each node holds a child mask; at a node present in both trees the walk
// takes the children in order k = 0..3: one both trees hold is visited, one
// only the environment holds is skipped with its subtree size, one only the
// transfer tree holds is skipped with its jump record when it has one, and
// otherwise read through without products (its subtree is short: the
// exporter gives jumps to long subtrees only; a leaf is skipped unread and
// a node whose children are leaves by its child count, records of a level
// having one size). I = S_A·S_B + Σ_{i ∈ A∩B} C_A^i · C_B^i per channel,
// then × albedo. Masked cells come out with alpha 0, sampled ones with
// alpha 1 + the transfer records read (the per-pixel work the page
// reports).
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp usampler2D;

uniform usampler2D u_line;    // the trees' 4-bit units, RGBA8UI, 8 a texel
uniform usampler2D u_blocks;  // per sampled cell·6 + face: first unit (or ~0u), scaling bits
uniform sampler2D u_cells;    // W×H: albedo RGB, A 0 masked / 1 + the cell's block row
uniform sampler2D u_env;      // environment nodes, 3 RGBA32F texels each
uniform int u_row;            // texels a row of u_line, u_blocks and u_env
uniform int u_levels;         // wavelet levels of a face (log2 N)
uniform int u_bits[8];        // code bits per level
uniform int u_units[8];       // record units per level
uniform int u_step_bias;      // of the step minifloat
uniform int u_env_offset[6];  // first node of each face's environment tree
uniform int u_env_count[6];   // its nodes (0: no wavelet node)
uniform vec3 u_env_scaling[6];

out vec4 o_color;

// Every iteration takes one child or returns to a parent: twice the nodes
// of both trees of the largest face (N = 256: (N² − 1)/3 each) bound a walk.
const int kMaxSteps = 87384;

uint wordAt(int w) {
  uvec4 t = texelFetch(u_line, ivec2(w % u_row, w / u_row), 0);
  return t.r | (t.g << 8) | (t.b << 16) | (t.a << 24);
}
// n ≤ 8 units of the stream from unit u (bits 4u .. 4u + 4n − 1) in the low
// bits (the bits above are what follows in the stream, or zero: callers
// mask). One texel fetch when the n units lie in one texel, else two.
uint fieldAt(int u, int n) {
  int s = (u & 7) * 4;
  uint lo = wordAt(u >> 3) >> uint(s);
  if (s == 0 || (u & 7) + n <= 8) return lo;
  return lo | (wordAt((u >> 3) + 1) << uint(32 - s));
}
vec4 envAt(int k) { return texelFetch(u_env, ivec2(k % u_row, k / u_row), 0); }

// The step of a level from its 8-bit code: the float32 with exponent
// code/8 − bias and mantissa (code mod 8)/8, exactly.
float stepOf(uint code) {
  if (code == 0u) return 0.0;
  uint e = uint(int(code >> 3u) - u_step_bias + 127);
  return uintBitsToFloat((e << 23) | ((code & 7u) << 20));
}

// A transfer node's coefficients dotted with environment node k's.
vec3 product(uint rec, int b, float step, int k) {
  uint m = (1u << uint(b)) - 1u;
  float bias = float(1 << (b - 1));
  vec3 c = (vec3(float(rec & m), float((rec >> uint(b)) & m), float((rec >> uint(2 * b)) & m)) -
            bias) * step;
  return c.x * envAt(3 * k).rgb + c.y * envAt(3 * k + 1).rgb + c.z * envAt(3 * k + 2).rgb;
}

vec3 faceProduct(int face, uvec2 block, inout int visited) {
  vec3 sum = uintBitsToFloat(block.y) * u_env_scaling[face];
  if (block.x == 0xFFFFFFFFu || u_env_count[face] == 0) return sum;
  int q = int(block.x);       // transfer unit
  // The step codes: 8 bits a level, four levels a 32-bit read.
  float steps[8];
  uint codes = fieldAt(q, 8), more = u_levels > 4 ? fieldAt(q + 8, 8) : 0u;
  for (int l = 0; l < 8; ++l)
    steps[l] = l < u_levels ? stepOf(((l < 4 ? codes : more) >> uint(8 * (l & 3))) & 255u) : 0.0;
  q += 2 * u_levels;
  int b = u_env_offset[face];  // environment node
  // The roots: both trees have one.
  uint rec = fieldAt(q, u_units[0]);
  int bits = u_bits[0];
  sum += product(rec, bits, steps[0], b);
  ++visited;
  uint remA = u_levels > 1 ? (rec >> uint(3 * bits)) & 15u : 0u;
  bool jump = u_levels > 2 && ((rec >> uint(3 * bits + 4)) & 1u) != 0u;
  uint remB = uint(envAt(3 * b).a + 0.5);
  q += u_units[0] + (jump ? 4 : 0);
  b += 1;
  // Children not yet taken of the current node at `level`: 4 bits a level.
  int level = 0;
  for (int it = 0; it < kMaxSteps; ++it) {
    uint sh = uint(4 * level);
    uint ra = (remA >> sh) & 15u, rb = (remB >> sh) & 15u, r = ra | rb;
    if (r == 0u) {
      if (level == 0) break;
      --level;
      continue;
    }
    uint bit = r & (~r + 1u);  // the lowest child left
    remA &= ~(bit << sh);
    remB &= ~(bit << sh);
    int cl = level + 1;
    if ((ra & bit) == 0u) {  // the environment's only: skip its subtree
      b += int(envAt(3 * b + 1).a + 0.5);
      continue;
    }
    bool both = (rb & bit) != 0u;
    if (!both && cl == u_levels - 1) {  // the transfer tree's only, a leaf: fixed size
      q += u_units[cl];
      continue;
    }
    rec = fieldAt(q, u_units[cl]);
    ++visited;
    bits = u_bits[cl];
    uint mask = cl < u_levels - 1 ? (rec >> uint(3 * bits)) & 15u : 0u;
    jump = cl < u_levels - 2 && ((rec >> uint(3 * bits + 4)) & 1u) != 0u;
    if (!both && jump) {  // the transfer tree's only, a long subtree: jump over it
      q += int(fieldAt(q + u_units[cl], 4) & 0xFFFFu);
      continue;
    }
    if (!both && cl == u_levels - 2) {  // its children are leaves: their count sizes it
      int leaves = int((mask & 1u) + ((mask >> 1) & 1u) + ((mask >> 2) & 1u) + (mask >> 3));
      q += u_units[cl] + leaves * u_units[cl + 1];
      continue;
    }
    uint maskB = 0u;
    if (both) {
      sum += product(rec, bits, steps[cl], b);
      maskB = uint(envAt(3 * b).a + 0.5);
      b += 1;
    }
    q += u_units[cl] + (jump ? 4 : 0);
    if ((mask | maskB) != 0u) {
      level = cl;
      remA |= mask << uint(4 * cl);
      remB |= maskB << uint(4 * cl);
    }
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
  int first = 6 * (int(cell.a) - 1);
  vec3 sum = vec3(0.0);
  int visited = 0;
  for (int face = 0; face < 6; ++face) {
    int k = first + face;
    sum += faceProduct(face, texelFetch(u_blocks, ivec2(k % u_row, k / u_row), 0).rg, visited);
  }
  o_color = vec4(sum * cell.rgb, 1.0 + float(visited));
}
