#include "runtime/io/stb_codecs.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

// Debian's headers, compiled here with internal linkage and only the two
// formats the project reads; warnings of the third-party code are not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
// (not STBI_WRITE_NO_STDIO: this version's HDR writer sits inside its #ifndef)
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace wavebake {
namespace {

// stb_image's readers do not stop at the end of their input: past it, its
// byte reader returns 0 forever, and the Radiance reader's RLE loop takes a
// run count of 0 as "copy nothing" and asks again (stbi__hdr_load, the
// "Dump" branch): a truncated .hdr spins forever. So the bytes come through
// callbacks that, asked for more at the end, hand out '\n' instead and
// remember it: a header ends at an empty line, a count of 10 makes progress,
// a scanline starting with 10 is read flat to the end of the image — every
// loop ends, after at most the image's size in bytes (bounded by
// CheckHdrSize), and the decode is refused as truncated.
//
// stb asks in two ways: refilling its read-ahead buffer (a short answer is
// normal there) and, for a block larger than what is buffered, directly for
// the missing part (a short answer there is already a read past the end).
class Source {
 public:
  explicit Source(std::span<const std::byte> bytes) : bytes_(bytes) {}
  bool read_past_end() const { return past_end_; }
  static const stbi_io_callbacks* Callbacks() {
    static constexpr stbi_io_callbacks kCallbacks{&Read, &Skip, &Eof};
    return &kCallbacks;
  }

 private:
  static constexpr size_t kReadAhead = sizeof(stbi__context::buffer_start);

  static int Read(void* user, char* out, int size) {
    auto* s = static_cast<Source*>(user);
    const size_t want = static_cast<size_t>(size);
    const size_t n = std::min(want, s->bytes_.size() - s->pos_);
    if (n == 0 || (n < want && want != kReadAhead)) {
      s->past_end_ = true;
      std::memcpy(out, s->bytes_.data() + s->pos_, n);
      std::memset(out + n, '\n', want - n);
      s->pos_ += n;
      return size;
    }
    std::memcpy(out, s->bytes_.data() + s->pos_, n);
    s->pos_ += n;
    return static_cast<int>(n);
  }
  static void Skip(void* user, int n) {
    auto* s = static_cast<Source*>(user);
    if (n < 0) {
      s->pos_ -= std::min(static_cast<size_t>(-static_cast<int64_t>(n)), s->pos_);
    } else {
      if (static_cast<size_t>(n) > s->bytes_.size() - s->pos_) s->past_end_ = true;
      s->pos_ = std::min(s->bytes_.size(), s->pos_ + static_cast<size_t>(n));
    }
  }
  static int Eof(void* user) {
    const auto* s = static_cast<const Source*>(user);
    return s->pos_ >= s->bytes_.size();
  }

  std::span<const std::byte> bytes_;
  size_t pos_ = 0;
  bool past_end_ = false;
};

const stbi_uc* Bytes(std::span<const std::byte> b) {
  return reinterpret_cast<const stbi_uc*>(b.data());
}

// Fewest bytes any encoding of a width × height Radiance image takes: flat
// RGBE below width 8 and from 32768 on, else per scanline a 4-byte header and,
// per channel, runs of at most 127 pixels in 2 bytes (stbi__hdr_load). A file
// shorter than that is truncated, and no header can make the decoder work
// (or allocate) far beyond the size of its file.
absl::Status CheckHdrSize(std::span<const std::byte> file, const std::string& name) {
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(Bytes(file), static_cast<int>(file.size()), &w, &h, &comp))
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": unreadable Radiance HDR: ", stbi_failure_reason()));
  if (w <= 0 || h <= 0)
    return absl::InvalidArgumentError(absl::StrCat(name, ": Radiance HDR of size ", w, "x", h));
  const int64_t row = (w < 8 || w >= 32768) ? int64_t{4} * w : 4 + 8 * ((int64_t{w} + 126) / 127);
  if (static_cast<int64_t>(file.size()) < row * h)
    return absl::InvalidArgumentError(absl::StrCat(name, ": truncated Radiance HDR: ", w, "x", h,
                                                   " pixels need at least ", row * h,
                                                   " bytes, the file has ", file.size()));
  return absl::OkStatus();
}

// stb trusts a chunk's declared length: it grows its IDAT buffer to that
// length and then asks for the bytes, so a 168-byte file declaring a 2 GB
// IDAT made it allocate and fill 2 GB (tests/fuzz/png). Every chunk up to
// IEND must fit in the file (PNG spec §5.3: length, type, data, CRC).
absl::Status CheckPngChunks(std::span<const std::byte> file, const std::string& name) {
  static constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
  if (file.size() < 8 || std::memcmp(file.data(), kSignature, 8) != 0)
    return absl::InvalidArgumentError(absl::StrCat(name, ": not a PNG file (no PNG signature)"));
  const auto u8 = [&](size_t i) { return std::to_integer<uint32_t>(file[i]); };
  size_t at = 8;
  while (at + 12 <= file.size()) {
    const uint64_t length = u8(at) << 24 | u8(at + 1) << 16 | u8(at + 2) << 8 | u8(at + 3);
    const std::string type(reinterpret_cast<const char*>(file.data()) + at + 4, 4);
    if (length > file.size() - at - 12)
      return absl::InvalidArgumentError(absl::StrCat(
          name, ": truncated PNG: chunk '", absl::CEscape(type), "' at byte ", at, " declares ",
          length, " bytes, the file has ", file.size() - at - 12, " left"));
    if (type == "IEND") return absl::OkStatus();
    at += 12 + length;
  }
  return absl::InvalidArgumentError(absl::StrCat(name, ": truncated PNG (no IEND chunk)"));
}

void AppendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::byte>*>(context);
  const auto* p = static_cast<const std::byte*>(data);
  out->insert(out->end(), p, p + size);
}

absl::Status CheckRgbSize(int width, int height, size_t values) {
  if (width > 0 && height > 0 && values == size_t(width) * height * 3) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat("image ", width, "x", height, " needs ",
                                                 size_t(width) * height * 3, " values, got ",
                                                 values));
}

}  // namespace

absl::StatusOr<EnvMap> DecodeRadianceHdr(std::span<const std::byte> file, const std::string& name) {
  if (file.size() > size_t{1} << 31)
    return absl::InvalidArgumentError(absl::StrCat(name, ": larger than 2 GiB"));
  if (!stbi_is_hdr_from_memory(Bytes(file), static_cast<int>(file.size())))
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": not a Radiance HDR file (no #?RADIANCE or #?RGBE header)"));
  if (absl::Status s = CheckHdrSize(file, name); !s.ok()) return s;
  Source source(file);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<float, void (*)(void*)> data(
      stbi_loadf_from_callbacks(Source::Callbacks(), &source, &w, &h, &channels, 3),
      stbi_image_free);
  if (source.read_past_end())
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": truncated Radiance HDR (the pixels end before ", w, "x", h, ")"));
  if (!data)
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": unreadable Radiance HDR: ", stbi_failure_reason()));
  return EnvMap{w, h, std::vector<float>(data.get(), data.get() + size_t(w) * h * 3)};
}

absl::StatusOr<std::vector<std::byte>> EncodeRadianceHdr(int width, int height,
                                                         std::span<const float> rgb) {
  if (absl::Status s = CheckRgbSize(width, height, rgb.size()); !s.ok()) return s;
  std::vector<std::byte> out;
  if (!stbi_write_hdr_to_func(AppendBytes, &out, width, height, 3, rgb.data()))
    return absl::InternalError("Radiance HDR encoding failed");
  return out;
}

absl::StatusOr<Rgb8Image> DecodePng(std::span<const std::byte> file, const std::string& name) {
  if (file.size() > size_t{1} << 31)
    return absl::InvalidArgumentError(absl::StrCat(name, ": larger than 2 GiB"));
  // stb allocates the decoded size the header declares before inflating: a
  // tiny file must not make a huge buffer. Deflate packs at most ~1032 bytes
  // in one, so no PNG holds more than ~1032 pixels per byte of its own.
  int w = 0, h = 0, comp = 0;
  if (stbi_info_from_memory(Bytes(file), static_cast<int>(file.size()), &w, &h, &comp)) {
    const int64_t limit =
        std::min(int64_t{1} << 27, std::max(int64_t{1} << 20, 1032 * int64_t(file.size())));
    if (int64_t{w} * h > limit)
      return absl::InvalidArgumentError(absl::StrCat(name, ": PNG of ", w, "x", h,
                                                     " pixels in a file of ", file.size(),
                                                     " bytes (at most ", limit, ")"));
  }
  if (absl::Status s = CheckPngChunks(file, name); !s.ok()) return s;
  Source source(file);
  Rgb8Image image;
  int channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_callbacks(Source::Callbacks(), &source, &image.width, &image.height, &channels,
                               3),
      stbi_image_free);
  if (source.read_past_end())
    return absl::InvalidArgumentError(absl::StrCat(name, ": truncated PNG"));
  if (!data)
    return absl::InvalidArgumentError(
        absl::StrCat(name, ": unreadable PNG: ", stbi_failure_reason()));
  image.rgb.assign(data.get(), data.get() + size_t(image.width) * image.height * 3);
  return image;
}

absl::StatusOr<std::vector<std::byte>> EncodePng(int width, int height, int channels,
                                                 std::span<const uint8_t> pixels) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      pixels.size() != size_t(width) * height * channels)
    return absl::InvalidArgumentError(absl::StrCat("png: ", width, "x", height, "x", channels,
                                                   " does not match ", pixels.size(), " bytes"));
  std::vector<std::byte> out;
  if (!stbi_write_png_to_func(AppendBytes, &out, width, height, channels, pixels.data(),
                              width * channels))
    return absl::InternalError("PNG encoding failed");
  return out;
}

}  // namespace wavebake
