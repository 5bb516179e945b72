// OpenEXR bytes through DecodeExr (runtime/io/image_io.h) and the checks
// LoadEnvMap applies after it: no crash, no endless loop; errors name the file.
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstring>

#include "runtime/io/image_io.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {
namespace {

class StringOStream : public Imf::OStream {
 public:
  StringOStream() : Imf::OStream("seed") {}
  void write(const char c[], int n) override {
    if (pos_ + n > bytes.size()) bytes.resize(pos_ + n);
    std::memcpy(bytes.data() + pos_, c, n);
    pos_ += n;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  std::string bytes;

 private:
  uint64_t pos_ = 0;
};

// A small image in each compression, R G B as float or half, or Y alone.
std::string Exr(int w, int h, Imf::Compression compression, Imf::PixelType type, bool luminance) {
  StringOStream stream;
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.25f * float(i % 11);
  std::vector<Imath::half> half(rgb.begin(), rgb.end());  // the slice's type is the channel's
  Imf::Header header(w, h);
  header.compression() = compression;
  Imf::FrameBuffer fb;
  const size_t item = type == Imf::HALF ? sizeof(Imath::half) : sizeof(float);
  const size_t xs = 3 * item, ys = xs * w;
  char* base = type == Imf::HALF ? reinterpret_cast<char*>(half.data())
                                 : reinterpret_cast<char*>(rgb.data());
  for (int c = 0; c < (luminance ? 1 : 3); ++c) {
    const char* name = luminance ? "Y" : (c == 0 ? "R" : (c == 1 ? "G" : "B"));
    header.channels().insert(name, Imf::Channel(type));
    fb.insert(name, Imf::Slice(type, base + c * item, xs, ys));
  }
  Imf::OutputFile file(stream, header);
  file.setFrameBuffer(fb);
  file.writePixels(h);
  return stream.bytes;
}

}  // namespace

std::vector<std::string> Seeds() {
  return {Exr(4, 2, Imf::NO_COMPRESSION, Imf::FLOAT, false),
          Exr(8, 4, Imf::ZIP_COMPRESSION, Imf::FLOAT, false),
          Exr(8, 4, Imf::RLE_COMPRESSION, Imf::HALF, false),
          Exr(16, 8, Imf::PIZ_COMPRESSION, Imf::HALF, false),
          Exr(6, 3, Imf::ZIPS_COMPRESSION, Imf::FLOAT, true)};
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using wavebake::fuzz::Require;
  const auto bytes = std::as_bytes(std::span(reinterpret_cast<const char*>(data), size));
  absl::StatusOr<wavebake::EnvMap> env = wavebake::DecodeExr(bytes, "f.exr");
  if (!env.ok()) {
    Require(env.status().message().find("f.exr") != std::string::npos, "error names the file");
    return 0;
  }
  Require(env->width > 0 && env->height > 0, "positive size");
  Require(env->rgb.size() == size_t(env->width) * env->height * 3, "3 floats per pixel");
  return 0;
}
