#include "worker/columns/group_result.h"

#include <array>
#include <cstring>
#include <span>
#include <string>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zstd_codec.h"
#include "worker/columns/shard_plan.h"

namespace wavebake {
namespace {

constexpr char kMagic[8] = {'W', 'B', 'G', 'R', 'O', 'U', 'P', '3'};

// Group results live until FINALIZE reads them and are dropped with staging:
// a fast level. Their float values hardly compress at any level.
constexpr int kGroupResultZstdLevel = -3;

// The compressed sizes of the frames after the magic, in file order.
enum Frame { kTableFrame, kPositionsFrame, kValuesFrame, kFrames };
struct Preamble {
  std::array<uint64_t, kFrames> frame_bytes{};
  uint64_t End(int frame) const {  // the file offset just past `frame`
    uint64_t end = sizeof kMagic + sizeof frame_bytes;
    for (int f = 0; f <= frame; ++f) end += frame_bytes[f];
    return end;
  }
};
constexpr size_t kPreambleBytes = sizeof kMagic + sizeof Preamble::frame_bytes;
// A corrupt size must not become a huge allocation or read. A table holds
// 48 bytes per column, and a group has at most the M ≤ 6·256² columns of a job.
constexpr uint64_t kMaxFrameBytes = uint64_t{1} << 36;
constexpr uint64_t kMaxTableBytes = uint64_t{1} << 26;

// Appends plain values as their little-endian bytes (the host order, dtype.h).
class ByteWriter {
 public:
  template <class T>
  void Put(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  std::vector<std::byte>& bytes() { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

// Reads them back; any read past the end marks the reader bad.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> b) : bytes_(b) {}
  template <class T>
  T Get() {
    T v{};
    GetInto(std::as_writable_bytes(std::span(&v, 1)));
    return v;
  }
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == bytes_.size(); }

 private:
  void GetInto(std::span<std::byte> out) {
    if (!ok_ || out.size() > bytes_.size() - pos_) {
      ok_ = false;
      return;
    }
    std::memcpy(out.data(), bytes_.data() + pos_, out.size());
    pos_ += out.size();
  }
  std::span<const std::byte> bytes_;
  size_t pos_ = 0;
  bool ok_ = true;
};

std::vector<std::byte> Table(const GroupResult& r) {
  ByteWriter w;
  w.Put<int32_t>(r.group);
  w.Put<int32_t>(r.first_column);
  w.Put<int32_t>(static_cast<int32_t>(r.columns.size()));
  w.Put<int32_t>(0);
  w.Put<uint64_t>(r.positions.size());
  w.Put<double>(r.matrix_energy);
  for (const GroupColumn& c : r.columns) {
    w.Put(c.depth);
    w.Put(c.min_bits);
    w.Put<uint16_t>(0);
    w.Put(c.kept);
    w.Put(c.energy);
    w.Put(c.reference_energy);
    w.Put(c.dropped_energy);
    w.Put(c.max_abs);
    w.Put(c.step_unit);
  }
  return std::move(w.bytes());
}

// The table into `r` (header and columns); returns nnz, checked against the
// columns' kept counts.
absl::StatusOr<uint64_t> ParseTable(std::span<const std::byte> bytes, const std::string& source,
                                    GroupResult* r) {
  ByteReader rd(bytes);
  r->group = rd.Get<int32_t>();
  r->first_column = rd.Get<int32_t>();
  const int32_t count = rd.Get<int32_t>();
  rd.Get<int32_t>();
  const uint64_t nnz = rd.Get<uint64_t>();
  r->matrix_energy = rd.Get<double>();
  if (!rd.ok() || count < 0 || uint64_t(count) > bytes.size())
    return absl::DataLossError(absl::StrCat(source, ": bad group header"));
  r->columns.resize(count);
  uint64_t kept_sum = 0;
  for (GroupColumn& c : r->columns) {
    c.depth = rd.Get<uint8_t>();
    c.min_bits = rd.Get<uint8_t>();
    rd.Get<uint16_t>();
    c.kept = rd.Get<uint32_t>();
    c.energy = rd.Get<double>();
    c.reference_energy = rd.Get<double>();
    c.dropped_energy = rd.Get<double>();
    c.max_abs = rd.Get<double>();
    c.step_unit = rd.Get<double>();
    kept_sum += c.kept;
  }
  if (!rd.ok() || !rd.at_end() || kept_sum != nnz)
    return absl::DataLossError(absl::StrCat(source, ": group table is inconsistent"));
  return nnz;
}

absl::StatusOr<Preamble> ParsePreamble(std::span<const std::byte> head, const std::string& source) {
  if (head.size() < kPreambleBytes || std::memcmp(head.data(), kMagic, sizeof kMagic) != 0)
    return absl::DataLossError(absl::StrCat(source, ": not a group result (bad magic)"));
  Preamble p;
  std::memcpy(p.frame_bytes.data(), head.data() + sizeof kMagic, sizeof p.frame_bytes);
  for (uint64_t bytes : p.frame_bytes)
    if (bytes > kMaxFrameBytes)
      return absl::DataLossError(absl::StrCat(source, ": frame size ", bytes));
  return p;
}

// Decompresses one frame into `out`, resized to the `bytes` the (checksummed)
// table expects; ZstdDecompressInto refuses a frame that declares another size.
template <class Vector>
absl::Status DecompressFrame(std::span<const std::byte> frame, uint64_t bytes,
                             const std::string& source, Vector& out) {
  out.resize(bytes / sizeof(typename Vector::value_type));
  return ZstdDecompressInto(frame, std::as_writable_bytes(std::span(out)), source);
}

// The table frame, decompressed and parsed into `r` and checked to be
// `group`'s; returns nnz.
absl::StatusOr<uint64_t> ReadTable(std::span<const std::byte> frame, const std::string& source,
                                   int group, GroupResult* r) {
  thread_local ByteBuffer table;
  absl::StatusOr<uint64_t> size = ZstdFrameContentSize(frame, source);
  if (!size.ok()) return size.status();
  if (*size > kMaxTableBytes)
    return absl::DataLossError(absl::StrCat(source, ": table size ", *size));
  table.resize(*size);
  if (absl::Status s = ZstdDecompressInto(frame, table, source); !s.ok()) return s;
  absl::StatusOr<uint64_t> nnz = ParseTable(table, source, r);
  if (nnz.ok() && r->group != group)
    return absl::DataLossError(absl::StrCat(source, ": holds group ", r->group));
  return nnz;
}

}  // namespace

void AppendColumn(const CodedColumn& coded, GroupResult* result) {
  GroupColumn c;
  c.depth = static_cast<uint8_t>(coded.depth);
  c.min_bits = static_cast<uint8_t>(coded.min_bits);
  c.kept = static_cast<uint32_t>(coded.positions.size());
  c.energy = coded.energy;
  c.reference_energy = coded.reference_energy;
  c.dropped_energy = coded.dropped_energy;
  c.max_abs = coded.max_abs;
  c.step_unit = coded.step_unit;
  result->columns.push_back(c);
  result->positions.insert(result->positions.end(), coded.positions.begin(), coded.positions.end());
  result->values.insert(result->values.end(), coded.values.begin(), coded.values.end());
}

std::filesystem::path GroupResultDir(const std::filesystem::path& store) {
  return store::Path(store, store::kStagingGroups);
}

std::filesystem::path GroupResultPath(const std::filesystem::path& store, int group) {
  return GroupResultDir(store) / absl::StrCat(group, ".wbg");
}

absl::Status WriteGroupResult(const std::filesystem::path& store, const GroupResult& result) {
  // A FINALIZE plan worked out from the group results before is not this one's.
  if (absl::Status s = RemoveShardPlan(store); !s.ok()) return s;
  const std::vector<std::byte> table = Table(result);
  thread_local std::array<ByteBuffer, kFrames> frames;
  const std::array<std::span<const std::byte>, kFrames> raw = {
      table, std::as_bytes(std::span(result.positions)), std::as_bytes(std::span(result.values))};
  Preamble p;
  for (int f = 0; f < kFrames; ++f) {
    if (absl::Status s = ZstdCompressInto(raw[f], kGroupResultZstdLevel, frames[f]); !s.ok())
      return s;
    p.frame_bytes[f] = frames[f].size();
  }
  std::array<std::byte, kPreambleBytes> head;
  std::memcpy(head.data(), kMagic, sizeof kMagic);
  std::memcpy(head.data() + sizeof kMagic, p.frame_bytes.data(), sizeof p.frame_bytes);
  const std::array<std::span<const std::byte>, 1 + kFrames> parts = {head, frames[0], frames[1],
                                                                     frames[2]};
  if (absl::Status s = CreateDirectories(GroupResultDir(store)); !s.ok()) return s;
  return AtomicWriteFileParts(GroupResultPath(store, result.group), parts);
}

absl::StatusOr<GroupResult> ReadGroupResult(const std::filesystem::path& store, int group) {
  const std::filesystem::path path = GroupResultPath(store, group);
  const std::string source = path.string();
  // A per-thread buffer, reused group after group (storage/zarr/byte_buffer.h).
  thread_local ByteBuffer file;
  if (absl::Status s = ReadFileInto(path, file); !s.ok()) return s;
  absl::StatusOr<Preamble> p = ParsePreamble(file, source);
  if (!p.ok()) return p.status();
  if (file.size() != p->End(kValuesFrame))
    return absl::DataLossError(
        absl::StrCat(source, ": ", file.size(), " bytes, the frames need ", p->End(kValuesFrame)));
  auto frame = [&](int f) {
    const uint64_t end = p->End(f);
    return std::span<const std::byte>(file).subspan(end - p->frame_bytes[f], p->frame_bytes[f]);
  };
  GroupResult r;
  absl::StatusOr<uint64_t> nnz = ReadTable(frame(kTableFrame), source, group, &r);
  if (!nnz.ok()) return nnz.status();
  if (absl::Status s =
          DecompressFrame(frame(kPositionsFrame), *nnz * sizeof(uint32_t), source, r.positions);
      !s.ok())
    return s;
  if (absl::Status s = DecompressFrame(frame(kValuesFrame), *nnz * sizeof(float), source, r.values);
      !s.ok())
    return s;
  return r;
}

absl::StatusOr<GroupResult> ReadGroupColumns(const std::filesystem::path& store, int group) {
  const std::filesystem::path path = GroupResultPath(store, group);
  const std::string source = path.string();
  thread_local ByteBuffer head, frame;
  absl::Status read = ReadFileRangeInto(path, 0, kPreambleBytes, head);
  if (absl::IsOutOfRange(read)) return ParsePreamble({}, source).status();  // too short: bad magic
  if (!read.ok()) return read;
  absl::StatusOr<Preamble> p = ParsePreamble(head, source);
  if (!p.ok()) return p.status();
  read = ReadFileRangeInto(path, kPreambleBytes, p->frame_bytes[kTableFrame], frame);
  if (absl::IsOutOfRange(read))
    return absl::DataLossError(absl::StrCat(source, ": truncated: ", read.message()));
  if (!read.ok()) return read;
  GroupResult r;
  absl::StatusOr<uint64_t> nnz = ReadTable(frame, source, group, &r);
  if (!nnz.ok()) return nnz.status();
  return r;
}

}  // namespace wavebake
