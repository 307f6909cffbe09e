#include "io/image_decode.h"

// OIIO headers define FMT_HEADER_ONLY and disable fmt exceptions; keep them after anything
// that includes fmt (see ../shared/notes/debian-deps.md).
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <memory>

#include "core/memory_limit.h"
#include "io/errors.h"

namespace prism {

float srgb_to_linear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

namespace {

// Bounds the pixels a texture may have before anything is allocated (64k x 64k).
constexpr uint64_t kMaxTexels = uint64_t(1) << 32;

ImageDesc read_from(OIIO::ImageInput* in, ColorSpace space, const std::string& file, const std::string& element) {
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 ||
      uint64_t(spec.width) * uint64_t(spec.height) > kMaxTexels)
    throw InputError(file, element, "image has an unusable size " + std::to_string(spec.width) + "x" +
                                        std::to_string(spec.height) + "x" + std::to_string(spec.nchannels));
  require_memory(uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(std::min(spec.nchannels, 4)) * sizeof(float),
                 element.empty() ? file : file + ": " + element);
  ImageDesc img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = std::min(spec.nchannels, 4);
  img.texels.resize(size_t(img.width) * img.height * img.channels);
  if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.texels.data()))
    throw InputError(file, element, "cannot decode image: " + in->geterror());
  if (space == ColorSpace::Auto) {
    const auto base = spec.format.basetype;
    const bool is_float = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE;
    space = is_float ? ColorSpace::Linear : ColorSpace::Srgb;
  }
  if (space == ColorSpace::Srgb) {
    // Alpha is linear coverage: in 2- and 4-channel images the last channel is left as is.
    const int colour = (img.channels == 2 || img.channels == 4) ? img.channels - 1 : img.channels;
    for (size_t i = 0; i < img.texels.size(); i += img.channels)
      for (int c = 0; c < colour; ++c) img.texels[i + c] = srgb_to_linear(img.texels[i + c]);
  }
  return img;
}

}  // namespace

ImageDesc decode_image(const unsigned char* data, size_t size, ColorSpace space, const std::string& file,
                       const std::string& element) {
  if (size == 0) throw InputError(file, element, "image has no data");
  OIIO::Filesystem::IOMemReader reader(const_cast<unsigned char*>(data), size);
  // The name only helps OIIO guess; it sniffs the bytes when the guess is wrong.
  auto in = OIIO::ImageInput::open("image.png", nullptr, &reader);
  if (!in) throw InputError(file, element, "cannot decode image: " + OIIO::geterror());
  return read_from(in.get(), space, file, element);
}

ImageDesc read_image_file(const std::string& path, ColorSpace space) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
  ImageDesc img = read_from(in.get(), space, path, "");
  img.name = path;
  return img;
}

}  // namespace prism
