// The image codecs module (libprism_image_codecs.so): ImageCodecs through OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

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
    return info;
  }

  bool read(int channels, ImageCodecs::Samples kind, void* texels, std::string& error) override {
    const OIIO::TypeDesc type = kind == ImageCodecs::Samples::Uint8    ? OIIO::TypeDesc::UINT8
                                : kind == ImageCodecs::Samples::Uint16 ? OIIO::TypeDesc::UINT16
                                : kind == ImageCodecs::Samples::Half   ? OIIO::TypeDesc::HALF
                                                                       : OIIO::TypeDesc::FLOAT;
    if (in_->read_image(0, 0, 0, channels, type, texels)) return true;
    error = in_->geterror();
    return false;
  }

 private:
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

extern "C" __attribute__((visibility("default"))) const prism::ImageCodecs* prism_image_codecs_v3() {
  static const prism::OiioCodecs codecs;
  return &codecs;
}
