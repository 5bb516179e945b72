#include "worker/group_result.h"

#include <cstring>
#include <span>
#include <string>

#include "absl/strings/str_cat.h"
#include "storage/atomic_file.h"
#include "storage/store_layout.h"
#include "storage/zstd_codec.h"

namespace wavebake {
namespace {

constexpr char kMagic[8] = {'W', 'B', 'G', 'R', 'O', 'U', 'P', '2'};

// Group results live until FINALIZE reads them (twice) and are dropped with
// staging: a fast level. Their float values hardly compress at any level.
constexpr int kGroupResultZstdLevel = -3;
constexpr size_t kPreamble = sizeof kMagic + sizeof(uint64_t);

// Appends plain values as their little-endian bytes (the host order, dtype.h).
class ByteWriter {
 public:
  template <class T>
  void Put(const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <class T>
  void PutAll(const std::vector<T>& v) {
    const auto b = std::as_bytes(std::span(v));
    bytes_.insert(bytes_.end(), b.begin(), b.end());
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
  template <class T>
  void GetAll(std::vector<T>& v, size_t n) {
    if (n > (bytes_.size() - pos_) / sizeof(T)) {
      ok_ = false;
      return;
    }
    v.resize(n);
    GetInto(std::as_writable_bytes(std::span(v)));
  }
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == bytes_.size(); }

 private:
  void GetInto(std::span<std::byte> out) {
    if (!ok_ || out.size() > bytes_.size() - pos_) {
      ok_ = false;
      return;
    }
    // An empty vector's data() may be null, which memcpy may not be given
    // even for 0 bytes (a group whose columns kept nothing).
    if (out.empty()) return;
    std::memcpy(out.data(), bytes_.data() + pos_, out.size());
    pos_ += out.size();
  }
  std::span<const std::byte> bytes_;
  size_t pos_ = 0;
  bool ok_ = true;
};

std::vector<std::byte> Payload(const GroupResult& r) {
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
  w.PutAll(r.positions);
  w.PutAll(r.values);
  return std::move(w.bytes());
}

absl::StatusOr<GroupResult> ParsePayload(std::span<const std::byte> bytes,
                                         const std::string& source) {
  ByteReader rd(bytes);
  GroupResult r;
  r.group = rd.Get<int32_t>();
  r.first_column = rd.Get<int32_t>();
  const int32_t count = rd.Get<int32_t>();
  rd.Get<int32_t>();
  const uint64_t nnz = rd.Get<uint64_t>();
  r.matrix_energy = rd.Get<double>();
  if (!rd.ok() || count < 0 || nnz > bytes.size())
    return absl::DataLossError(absl::StrCat(source, ": bad group header"));
  r.columns.resize(count);
  uint64_t kept_sum = 0;
  for (GroupColumn& c : r.columns) {
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
  rd.GetAll(r.positions, nnz);
  rd.GetAll(r.values, nnz);
  if (!rd.ok() || !rd.at_end() || kept_sum != nnz)
    return absl::DataLossError(absl::StrCat(source, ": group payload is inconsistent"));
  return r;
}

}  // namespace

std::filesystem::path GroupResultDir(const std::filesystem::path& store) {
  return store::Path(store, store::kStagingGroups);
}

std::filesystem::path GroupResultPath(const std::filesystem::path& store, int group) {
  return GroupResultDir(store) / absl::StrCat(group, ".wbg");
}

absl::Status WriteGroupResult(const std::filesystem::path& store, const GroupResult& result) {
  const std::vector<std::byte> payload = Payload(result);
  ByteBuffer frame;
  if (absl::Status s = ZstdCompressInto(payload, kGroupResultZstdLevel, frame); !s.ok()) return s;
  ByteWriter file;
  for (char c : kMagic) file.Put(c);
  file.Put<uint64_t>(payload.size());
  std::vector<std::byte>& bytes = file.bytes();
  bytes.insert(bytes.end(), frame.begin(), frame.end());
  if (absl::Status s = CreateDirectories(GroupResultDir(store)); !s.ok()) return s;
  return AtomicWriteFile(GroupResultPath(store, result.group), bytes);
}

absl::StatusOr<GroupResult> ReadGroupResult(const std::filesystem::path& store, int group) {
  const std::filesystem::path path = GroupResultPath(store, group);
  // Per-thread buffers, reused group after group (storage/byte_buffer.h);
  // ParsePayload copies the result out of them.
  thread_local ByteBuffer file, payload;
  if (absl::Status s = ReadFileInto(path, file); !s.ok()) return s;
  const std::string source = path.string();
  if (file.size() < kPreamble || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    return absl::DataLossError(absl::StrCat(source, ": not a group result (bad magic)"));
  uint64_t payload_size = 0;
  std::memcpy(&payload_size, file.data() + sizeof kMagic, sizeof payload_size);
  if (payload_size > (uint64_t{1} << 36))  // a corrupt size must not become a huge allocation
    return absl::DataLossError(absl::StrCat(source, ": payload size ", payload_size));
  payload.resize(payload_size);
  if (absl::Status s = ZstdDecompressInto(std::span(file).subspan(kPreamble), payload, source);
      !s.ok()) {
    payload = {};  // a corrupt size must not stay reserved either
    return s;
  }
  absl::StatusOr<GroupResult> result = ParsePayload(payload, source);
  if (result.ok() && result->group != group)
    return absl::DataLossError(absl::StrCat(source, ": holds group ", result->group));
  return result;
}

}  // namespace wavebake
