// The JSON header of a wavelet-tree export (runtime/gpu/wavelet_tree.h):
// every array's file, type, shape and meaning, and the conventions a third
// party needs to write a loader.
#include <cmath>

#include "runtime/gpu/wavelet_tree.h"

namespace wavebake {

nlohmann::json WaveletTreeHeader(const WaveletTreeTextures& t, const nlohmann::json& source) {
  using nlohmann::json;
  const int64_t blocks = 6 * t.sampled;
  json h;
  h["format"] = kWaveletTreeFormat;
  h["source"] = source;
  h["width"] = t.width;
  h["height"] = t.height;
  h["light_res"] = t.light_res;
  h["levels"] = t.levels;
  h["sampled"] = t.sampled;
  h["code_bits"] = t.code_bits;
  h["record_units"] = t.record_nibbles;
  h["step_bias"] = t.step_bias;
  h["settings"] = {{"cut_off", t.cut_off},
                   {"target_error", t.target_error >= 0 ? json(t.target_error) : json(nullptr)},
                   {"bits", t.default_bits ? json("auto") : json(t.code_bits)},
                   {"level_weight", t.level_weight},
                   {"jump_nodes", t.jump_nodes}};
  h["line"] = {{"file", "line.bin"},
               {"units", t.line_nibbles},
               {"texels", t.line_texels},
               {"width", kTreeLineWidth},
               {"height", WaveletTreeTextures::RowsFor(t.line_texels)},
               {"type", "uint8"},
               {"channels", 4},
               {"webgl", "RGBA8UI / RGBA_INTEGER / UNSIGNED_BYTE"},
               {"meaning",
                "the trees as one stream of 4-bit units: unit u is the low half of byte "
                "u div 2 when u is even, its high half when odd; a field of k bits at unit u "
                "is bits 4u .. 4u+k-1 of the stream read as one little-endian number "
                "(a texel's R, G, B, A are bytes 4k .. 4k+3: texel k holds units 8k .. "
                "8k+7, bits 0-31 of the word R | G<<8 | B<<16 | A<<24). Texel k at "
                "(k mod width, k div width); units past `units` are zero (padding, and "
                "at least one spare texel so a reader may fetch two texels at a time)"}};
  h["blocks"] = {{"file", "blocks.bin"},
                 {"texels", blocks},
                 {"width", kTreeLineWidth},
                 {"height", WaveletTreeTextures::RowsFor(blocks)},
                 {"type", "uint32"},
                 {"channels", 2},
                 {"webgl", "RG32UI / RG_INTEGER / UNSIGNED_INT"},
                 {"meaning",
                  "texel b = 6 r + face for the sampled cell of rank r (cells: A = 1 + r): "
                  "R the unit of the line where the tree starts, 4294967295 when the tree "
                  "has no wavelet node; G the face's scaling coefficient (float32 bits). "
                  "Trees lie in block order, each starting where the previous non-empty "
                  "one ends; texels past `texels` are zero"}};
  h["cells"] = {{"file", "cells.bin"},
                {"texels", int64_t{t.width} * t.height},
                {"width", t.width},
                {"height", t.height},
                {"type", "float32"},
                {"channels", 4},
                {"webgl", "RGBA32F / RGBA / FLOAT"},
                {"meaning",
                 "texel (x, y) = cell y·width + x, row 0 = the grid's row 0 (the top of the "
                 "image): albedo RGB; A = 0 masked, else 1 + r where r counts the sampled "
                 "cells before this one in cell order (its blocks are 6 r .. 6 r + 5)"}};
  h["conventions"] = {
      {"faces", "+X -X +Y -Y +Z -Z, OpenGL cube map orientation, N x N texels each"},
      {"row",
       "per face the 2D non-standard orthonormal Haar transform of the N x N row of T, "
       "full depth, Mallat layout (scaling coefficient at (0,0))"},
      {"node",
       "square (l, sx, sy), 0 <= sx, sy < 2^l, l = 0..levels-1: its coefficients type 0 "
       "at Mallat (2^l+sx, sy), type 1 at (sx, 2^l+sy), type 2 at (2^l+sx, 2^l+sy); its "
       "children k = 0..3 are (l+1, 2sx + (k mod 2), 2sy + (k div 2))"},
      {"pruning",
       "Boulton 4.4 without sibling groups: a node of level l is significant when "
       "max |c| * 2^(-level_weight * l) >= cut_off; a node is kept when it or a "
       "descendant is significant"},
      {"tree",
       "at the tree's first unit: levels step codes of 8 bits (level 0 first), then the "
       "kept nodes depth first from the root (0,0,0), each node's record followed by "
       "its jump record if its jump flag is set, then its kept children in order k"},
      {"steps",
       "step code s of a level: 0 means step 0; else step = (1 + (s mod 8)/8) * "
       "2^(s div 8 - step_bias) (exactly: the float32 with exponent field s div 8 - "
       "step_bias + 127 and mantissa (s mod 8) << 20)"},
      {"record",
       "a node of level l is record_units[l] units (4 bits each): with b = "
       "code_bits[l], bits 0..b-1, b..2b-1, 2b..3b-1 the codes of types 0, 1, 2; "
       "below the finest level (l < levels-1) bits 3b..3b+3 the child mask (bit k: child "
       "k is kept and follows); for l < levels-2 bit 3b+4 the jump flag; other bits 0"},
      {"jump",
       "16 bits (4 units) right after a record whose jump flag is set: units from the "
       "node's first unit to the first unit past its subtree (its record, jump and all "
       "its descendants). Only nodes of levels 1..levels-3 with children carry one"},
      {"decode",
       "c = (code - 2^(b-1)) * step of the node's level; codes 1 .. 2^b-1 (code 0 "
       "never occurs)"},
      {"relight",
       "B(cell) = albedo * sum over faces of (S_face * L_scaling + sum over kept nodes "
       "of c . L) with L the lighting's coefficients in the same basis"}};
  h["stats"] = {
      {"trees", t.stats.trees},
      {"empty_trees", t.stats.empty_trees},
      {"nodes_total", t.stats.nodes_total},
      {"nodes_kept", t.stats.nodes_kept},
      {"jumps", t.stats.jumps},
      {"rel_error_pruned",
       t.stats.energy_total > 0 ? std::sqrt(t.stats.energy_pruned / t.stats.energy_total) : 0.0},
      {"rel_error_quantized",
       t.stats.energy_total > 0 ? std::sqrt(t.stats.energy_quantized / t.stats.energy_total) : 0.0},
      {"bytes", t.bytes()},
      {"seconds", t.stats.seconds}};
  return h;
}

}  // namespace wavebake
