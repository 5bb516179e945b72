#include "runtime/io/exr_preflight.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string_view>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

// Bytes of the value of every attribute type OpenEXR reads by its type
// rather than by the declared size; -1: read by size (string, vectors,
// opaque), or parsed here (chlist, preview).
int FixedSize(std::string_view type) {
  static const std::map<std::string_view, int> sizes = {{"box2i", 16},
                                                        {"box2f", 16},
                                                        {"chromaticities", 32},
                                                        {"compression", 1},
                                                        {"deepImageState", 1},
                                                        {"double", 8},
                                                        {"envmap", 1},
                                                        {"float", 4},
                                                        {"int", 4},
                                                        {"keycode", 28},
                                                        {"lineOrder", 1},
                                                        {"m33f", 36},
                                                        {"m33d", 72},
                                                        {"m44f", 64},
                                                        {"m44d", 128},
                                                        {"rational", 8},
                                                        {"tiledesc", 9},
                                                        {"timecode", 8},
                                                        {"v2i", 8},
                                                        {"v2f", 8},
                                                        {"v2d", 16},
                                                        {"v3i", 12},
                                                        {"v3f", 12},
                                                        {"v3d", 24}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? -1 : it->second;
}

class Walker {
 public:
  Walker(std::span<const std::byte> file, const std::string& name) : file_(file), name_(name) {}

  absl::Status Run() {
    if (file_.size() < 8) return Bad("shorter than its 8-byte preamble");
    const uint32_t version = U32(4);
    // OpenEXR: names of at most 31 bytes, 255 with the long-names flag (bit 10).
    max_name_ = (version & 0x400) ? 255 : 31;
    pos_ = 8;
    for (int part = 0;; ++part) {
      if (absl::Status s = Header(part); !s.ok()) return s;
      if ((version & 0x1000) == 0) return absl::OkStatus();  // single part
      if (pos_ >= file_.size()) return Bad("the list of headers is cut short");
      if (file_[pos_] == std::byte{0}) return absl::OkStatus();  // the empty header ends it
    }
  }

 private:
  absl::Status Bad(const auto&... why) const {
    return absl::InvalidArgumentError(absl::StrCat(name_, ": unreadable EXR: ", why...));
  }
  uint32_t U32(size_t at) const {
    uint32_t v = 0;
    std::memcpy(&v, file_.data() + at, 4);  // little-endian, as EXR and x86
    return v;
  }
  size_t left() const { return file_.size() - pos_; }

  bool Text(std::string& out, int max) {
    out.clear();
    while (pos_ < file_.size() && file_[pos_] != std::byte{0}) {
      if (static_cast<int>(out.size()) == max) return false;
      out.push_back(static_cast<char>(file_[pos_++]));
    }
    if (pos_ >= file_.size()) return false;
    ++pos_;
    return true;
  }

  absl::Status Header(int part) {
    for (;;) {
      std::string attr, type;
      if (!Text(attr, max_name_)) return Bad("header ", part, ": an attribute name is cut short");
      if (attr.empty()) return absl::OkStatus();
      if (!Text(type, max_name_) || left() < 4) return Bad("attribute '", attr, "' is cut short");
      const int32_t size = static_cast<int32_t>(U32(pos_));
      pos_ += 4;
      if (size < 0 || static_cast<size_t>(size) > left())
        return Bad("attribute '", attr, "' claims ", size, " bytes, the file has ", left(),
                   " left");
      const int fixed = FixedSize(type);
      if (fixed >= 0 && size != fixed)
        return Bad("attribute '", attr, "' of type ", type, " has size ", size, ", not ", fixed);
      if (type == "chlist") {
        if (absl::Status s = Channels(attr, size); !s.ok()) return s;
      } else if (type == "preview") {
        const uint64_t w = size >= 8 ? U32(pos_) : 0, h = size >= 8 ? U32(pos_ + 4) : 0;
        if (size < 8 || w > uint64_t(size) || h > uint64_t(size) ||
            8 + 4 * w * h != static_cast<uint64_t>(size))
          return Bad("attribute '", attr, "': a preview image that is not its size");
      } else if (attr == "dataWindow" && type == "box2i") {
        const int64_t x0 = int32_t(U32(pos_)), y0 = int32_t(U32(pos_ + 4));
        const int64_t x1 = int32_t(U32(pos_ + 8)), y1 = int32_t(U32(pos_ + 12));
        const int64_t w = x1 - x0 + 1, h = y1 - y0 + 1;
        // Each side against the limit first: w·h of two 32-bit sides can
        // overflow 64 bits.
        const int64_t limit = ExrPixelLimit(file_.size());
        if (w <= 0 || h <= 0 || w > limit || h > limit || w * h > limit)
          return Bad("data window of ", w, "x", h, " pixels (at most ", limit, " for a file of ",
                     file_.size(), " bytes)");
      }
      pos_ += static_cast<size_t>(size);
    }
  }

  // name\0, int32 pixel type, uint8 linear, 3 reserved, int32 x and y
  // sampling, ... then an empty name: exactly `size` bytes.
  absl::Status Channels(const std::string& attr, int32_t size) {
    const size_t start = pos_, end = pos_ + static_cast<size_t>(size);
    for (;;) {
      std::string channel;
      if (pos_ >= end || !Text(channel, 255) || pos_ > end)
        return Bad("attribute '", attr, "': a channel name runs past the list");
      if (channel.empty()) break;
      if (end - pos_ < 16) return Bad("attribute '", attr, "': channel '", channel, "' cut short");
      pos_ += 16;
    }
    if (pos_ != end) return Bad("attribute '", attr, "' is not its declared size");
    pos_ = start;  // Header() steps over the value
    return absl::OkStatus();
  }

  std::span<const std::byte> file_;
  const std::string& name_;
  size_t pos_ = 0;
  int max_name_ = 31;
};

}  // namespace

int64_t ExrPixelLimit(size_t file_bytes) {
  return std::min(int64_t{1} << 27,
                  std::max(int64_t{1} << 20, 1024 * static_cast<int64_t>(file_bytes)));
}

absl::Status CheckExrHeaders(std::span<const std::byte> file, const std::string& name) {
  return Walker(file, name).Run();
}

}  // namespace wavebake
