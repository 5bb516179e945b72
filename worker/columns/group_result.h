#pragma once
// What one TRANSFORM_COLUMNS task leaves in staging for FINALIZE (DESIGN.md
// §2): the group's coded columns, unquantized (the bit count is a
// matrix-wide choice FINALIZE makes). Stored as one file per group,
// staging/groups/<g>.wbg, replaced atomically, so a retried task simply
// rewrites it. Format (little-endian): 8-byte magic "WBGROUP3", three uint64
// compressed sizes, then the three zstd frames (with checksums) they size, in
// this order:
//   table: int32 group, int32 first_column, int32 columns, int32 0,
//          uint64 nnz, double matrix_energy,
//          per column: uint8 depth, uint8 min_bits, uint16 0, uint32 kept,
//                      double energy, reference_energy, dropped_energy,
//                      max_abs, step_unit;
//   uint32 positions[nnz];  float values[nnz]   (columns concatenated in order).
// The table comes first and alone so that FINALIZE's first pass, which needs
// only the columns, reads and decompresses a few kilobytes per group instead
// of the whole group.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/columns/column_coding.h"
#include "storage/zarr/byte_buffer.h"

namespace wavebake {

struct GroupColumn {
  uint8_t depth = 0;
  uint8_t min_bits = 2;  // fewest bits meeting --bits auto for this column
  uint32_t kept = 0;     // its slice of GroupResult::positions/values
  double energy = 0;
  double reference_energy = 0;
  double dropped_energy = 0;
  double max_abs = 0;    // see CodedColumn (core/columns/column_coding.h)
  double step_unit = 0;  // see CodedColumn
};

struct GroupResult {
  int group = 0;
  int first_column = 0;
  double matrix_energy = 0;  // mean column energy of the matrix the group saw
  std::vector<GroupColumn> columns;
  // Empty after ReadGroupColumns. Default-initialized on growth: a read
  // decompresses straight into them (storage/zarr/byte_buffer.h).
  DefaultInitVector<uint32_t> positions;
  DefaultInitVector<float> values;
};

// Appends a coded column: its table entry and its positions and values.
void AppendColumn(const CodedColumn& coded, GroupResult* result);

std::filesystem::path GroupResultDir(const std::filesystem::path& store);
std::filesystem::path GroupResultPath(const std::filesystem::path& store, int group);

absl::Status WriteGroupResult(const std::filesystem::path& store, const GroupResult& result);
// NotFound if the group has not been written; DataLoss naming the file if it
// is corrupt or inconsistent.
absl::StatusOr<GroupResult> ReadGroupResult(const std::filesystem::path& store, int group);
// The same without positions and values: the header and the column table.
absl::StatusOr<GroupResult> ReadGroupColumns(const std::filesystem::path& store, int group);

}  // namespace wavebake
