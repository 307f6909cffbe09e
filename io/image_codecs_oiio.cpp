// The image codecs module (libprism_image_codecs.so): ImageCodecs through OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <optional>
#include <string_view>
#include <vector>

#include "core/rgbe.h"
#include "io/image_codecs.h"

namespace prism {
namespace {

class OiioInput final : public ImageCodecs::Input {
 public:
  // `memory` (may be null) backs `in`: declared first, it is destroyed after it.
  OiioInput(std::unique_ptr<OIIO::Filesystem::IOMemReader> memory, std::unique_ptr<OIIO::ImageInput> in)
      : memory_(std::move(memory)), in_(std::move(in)) {}

  ImageCodecs::Info info() const override {
    const OIIO::ImageSpec& spec = in_->spec();
    const auto base = spec.format.basetype;
    // Files whose channels differ in type (an EXR with half colour and float depth) list them.
    const auto every_channel = [&](OIIO::TypeDesc::BASETYPE type) {
      if (base != type) return false;
      for (const OIIO::TypeDesc& t : spec.channelformats)
        if (t.basetype != type) return false;
      return true;
    };
    ImageCodecs::Info info;
    info.width = spec.width;
    info.height = spec.height;
    info.channels = spec.nchannels;
    info.is_float = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE;
    info.is_8bit = every_channel(OIIO::TypeDesc::UINT8);
    info.is_16bit = every_channel(OIIO::TypeDesc::UINT16);
    info.is_half = every_channel(OIIO::TypeDesc::HALF);
    info.is_rgbe = std::string_view(in_->format_name()) == "hdr" && spec.nchannels == 3;
    return info;
  }

  bool read(int channels, ImageCodecs::Samples kind, void* texels, std::string& error) override {
    if (kind == ImageCodecs::Samples::Rgbe) return read_rgbe(channels, static_cast<RgbeTexel*>(texels), error);
    const OIIO::TypeDesc type = kind == ImageCodecs::Samples::Uint8    ? OIIO::TypeDesc::UINT8
                                : kind == ImageCodecs::Samples::Uint16 ? OIIO::TypeDesc::UINT16
                                : kind == ImageCodecs::Samples::Half   ? OIIO::TypeDesc::HALF
                                                                       : OIIO::TypeDesc::FLOAT;
    if (in_->read_image(0, 0, 0, channels, type, texels)) return true;
    error = in_->geterror();
    return false;
  }

 private:
  // Reads floats a band of rows at a time and packs each texel, so the whole image never exists
  // as floats.
  bool read_rgbe(int channels, RgbeTexel* texels, std::string& error) {
    const OIIO::ImageSpec& spec = in_->spec();
    if (channels != 3 || spec.nchannels != 3) {
      error = "RGBE texels need 3 channels";
      return false;
    }
    constexpr int kBand = 64;
    const size_t width = size_t(spec.width);
    std::vector<float> band(width * 3 * kBand);
    for (int y0 = 0; y0 < spec.height; y0 += kBand) {
      const int y1 = std::min(spec.height, y0 + kBand);
      if (!in_->read_scanlines(0, 0, spec.y + y0, spec.y + y1, 0, 0, 3, OIIO::TypeDesc::FLOAT, band.data())) {
        error = in_->geterror();
        return false;
      }
      for (size_t i = 0; i < size_t(y1 - y0) * width; ++i) {
        const std::optional<RgbeTexel> t = exact_rgbe({band[3 * i], band[3 * i + 1], band[3 * i + 2]});
        if (!t) {
          error = "a texel is not exactly an RGBE value";
          return false;
        }
        texels[size_t(y0) * width + i] = *t;
      }
    }
    return true;
  }

  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory_;
  std::unique_ptr<OIIO::ImageInput> in_;
};

class OiioCodecs final : public ImageCodecs {
 public:
  std::unique_ptr<Input> open_memory(const unsigned char* data, size_t size, std::string& error) const override {
    auto memory = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<unsigned char*>(data), size);
    // The name only helps OIIO guess; it sniffs the bytes when the guess is wrong.
    auto in = OIIO::ImageInput::open("image.png", nullptr, memory.get());
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioInput>(std::move(memory), std::move(in));
  }

  std::unique_ptr<Input> open_file(const std::string& path, std::string& error) const override {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioInput>(nullptr, std::move(in));
  }

  bool write_png(const std::string& path, int width, int height, const unsigned char* rgb,
                 std::string& error) const override {
    // The writer is chosen by format name: the path may be a temporary name without .png.
    auto writer = OIIO::ImageOutput::create("png");
    if (!writer) {
      error = "no PNG writer: " + OIIO::geterror();
      return false;
    }
    const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (writer->open(path, spec) && writer->write_image(OIIO::TypeDesc::UINT8, rgb) && writer->close()) return true;
    error = writer->geterror();
    return false;
  }
};

}  // namespace
}  // namespace prism

extern "C" __attribute__((visibility("default"))) const prism::ImageCodecs* prism_image_codecs_v4() {
  static const prism::OiioCodecs codecs;
  return &codecs;
}
