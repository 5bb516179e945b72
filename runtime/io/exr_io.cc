// OpenEXR half of image_io.h.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "runtime/io/exr_preflight.h"
#include "runtime/io/image_io.h"
#include "storage/files/atomic_file.h"

namespace wavebake {

namespace {

// OpenEXR writes through a seekable stream; collecting the bytes in memory
// lets the file appear atomically (and only when complete).
class MemoryOStream : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + n > bytes_.size()) bytes_.resize(pos_ + n);
    std::memcpy(bytes_.data() + pos_, c, n);
    pos_ += n;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  std::span<const std::byte> bytes() const { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
  uint64_t pos_ = 0;
};

// The bytes of an EXR file, read by OpenEXR as a stream (so a fuzzer or a
// caller with bytes in memory needs no file).
class MemoryIStream : public Imf::IStream {
 public:
  MemoryIStream(std::span<const std::byte> bytes, const std::string& name)
      : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || static_cast<uint64_t>(n) > bytes_.size() - pos_)
      throw std::runtime_error(absl::StrCat("Early end of file: ", n, " bytes wanted at ", pos_,
                                            ", ", bytes_.size(), " in the file"));
    std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
    pos_ += static_cast<uint64_t>(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = std::min<uint64_t>(pos, bytes_.size()); }

 private:
  std::span<const std::byte> bytes_;
  uint64_t pos_ = 0;
};

absl::Status CheckImageSize(const std::filesystem::path& path, int width, int height,
                            size_t values) {
  if (width <= 0 || height <= 0 || values != size_t(width) * height * 3) {
    return absl::InvalidArgumentError(absl::StrCat(path.string(), ": image ", width, "x", height,
                                                   " needs ", size_t(width) * height * 3,
                                                   " floats, got ", values));
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status WriteExr(const std::filesystem::path& path, int width, int height,
                      std::span<const float> rgb) {
  if (absl::Status s = CheckImageSize(path, width, height, rgb.size()); !s.ok()) return s;
  MemoryOStream stream;
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer fb;
    // Slices want a mutable pointer though writing only reads through it.
    char* base = reinterpret_cast<char*>(const_cast<float*>(rgb.data()));
    const size_t xs = 3 * sizeof(float), ys = xs * width;
    for (int c = 0; c < 3; ++c) {
      const char* name = c == 0 ? "R" : (c == 1 ? "G" : "B");
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      fb.insert(name, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
    }
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  } catch (const std::exception& e) {
    return absl::InternalError(absl::StrCat(path.string(), ": writing EXR failed: ", e.what()));
  }
  return AtomicWriteFile(path, stream.bytes());
}

absl::StatusOr<EnvMap> ReadExrImage(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return absl::NotFoundError(absl::StrCat(path.string(), ": no such file"));
  }
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return bytes.status();
  return DecodeExr(*bytes, path.string());
}

absl::StatusOr<EnvMap> DecodeExr(std::span<const std::byte> file, const std::string& name) {
  if (absl::Status s = CheckExrHeaders(file, name); !s.ok()) return s;  // before OpenEXR
  try {
    MemoryIStream stream(file, name);
    Imf::InputFile in(stream);
    const Imath::Box2i dw = in.header().dataWindow();
    const Imf::ChannelList& channels = in.header().channels();
    const bool has_rgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!has_rgb && !channels.findChannel("Y")) {
      return absl::InvalidArgumentError(
          absl::StrCat(name, ": EXR has neither R, G, B nor Y channels"));
    }
    const int64_t width = int64_t{dw.max.x} - dw.min.x + 1,
                  height = int64_t{dw.max.y} - dw.min.y + 1;
    // Also checked before OpenEXR read the header (exr_preflight.h).
    if (width <= 0 || height <= 0 || width * height > ExrPixelLimit(file.size()))
      return absl::InvalidArgumentError(
          absl::StrCat(name, ": EXR data window of ", width, "x", height, " pixels"));
    EnvMap image{static_cast<int>(width), static_cast<int>(height), {}};
    image.rgb.resize(size_t(image.width) * image.height * 3);
    Imf::FrameBuffer fb;
    const size_t xs = 3 * sizeof(float), ys = xs * image.width;
    for (int c = 0; c < 3; ++c) {
      const char* channel = has_rgb ? (c == 0 ? "R" : (c == 1 ? "G" : "B")) : "Y";
      fb.insert(channel, Imf::Slice::Make(Imf::FLOAT, &image.rgb[c], dw, xs, ys));
      if (!has_rgb) break;  // Y goes to red, then is copied below.
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    if (!has_rgb) {
      for (size_t i = 0; i < image.rgb.size(); i += 3)
        image.rgb[i + 1] = image.rgb[i + 2] = image.rgb[i];
    }
    return image;
  } catch (const std::exception& e) {
    return absl::InvalidArgumentError(absl::StrCat(name, ": unreadable EXR: ", e.what()));
  }
}

}  // namespace wavebake
