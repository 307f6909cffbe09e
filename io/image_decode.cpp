#include "io/image_decode.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "core/huge_pages.h"
#include "core/memory_limit.h"
#include "io/errors.h"
#include "io/image_codecs.h"

namespace prism {

namespace {

// Bounds the pixels a texture may have before anything is allocated (64k x 64k).
constexpr uint64_t kMaxTexels = uint64_t(1) << 32;

// `reopen` gives the image afresh, for a second read when the first one, as RGBE texels, is refused.
ImageDesc read_from(ImageCodecs::Input& in, const std::function<std::unique_ptr<ImageCodecs::Input>()>& reopen,
                    ColorSpace space, TexelStorage storage, const std::string& file, const std::string& element) {
  const ImageCodecs::Info spec = in.info();
  if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0 ||
      uint64_t(spec.width) * uint64_t(spec.height) > kMaxTexels)
    throw InputError(file, element, "image has an unusable size " + std::to_string(spec.width) + "x" +
                                        std::to_string(spec.height) + "x" + std::to_string(spec.channels));
  if (space == ColorSpace::Auto) space = spec.is_float ? ColorSpace::Linear : ColorSpace::Srgb;
  // Compact storage keeps 8-bit codes as they are, and linear halves and 16-bit codes (those to be
  // sRGB-decoded become floats: a table for 65536 codes would cost more than it saves).
  const bool compact = storage == TexelStorage::Compact;
  const bool as_bytes = compact && spec.is_8bit;
  const bool as_halves = compact && spec.is_half && space == ColorSpace::Linear;
  const bool as_words = compact && spec.is_16bit && space == ColorSpace::Linear;
  const bool as_rgbe = compact && spec.is_rgbe && space == ColorSpace::Linear;
  const uint64_t values = uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(std::min(spec.channels, 4));
  const std::string what = element.empty() ? file : file + ": " + element;
  ImageDesc img;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = std::min(spec.channels, 4);
  std::string error;
  const auto read = [&](ImageCodecs::Samples kind, void* texels) {
    if (!in.read(img.channels, kind, texels, error)) throw InputError(file, element, "cannot decode image: " + error);
  };
  if (as_rgbe) {
    require_memory(uint64_t(spec.width) * uint64_t(spec.height) * sizeof(RgbeTexel), what);
    resize_on_huge_pages(img.rgbe, img.texel_count());
    if (in.read(img.channels, ImageCodecs::Samples::Rgbe, img.rgbe.data(), error)) return img;
    // A texel that is not exactly an RGBE value (or data the read stopped at): read it as floats,
    // which report bad data as they always do.
    std::vector<RgbeTexel>().swap(img.rgbe);
    const std::unique_ptr<ImageCodecs::Input> again = reopen();
    if (!again) throw InputError(file, element, "cannot decode image: " + error);
    return read_from(*again, reopen, space, TexelStorage::Float, file, element);
  }
  require_memory(values * (as_bytes ? 1 : as_halves || as_words ? sizeof(uint16_t) : sizeof(float)), what);
  if (as_bytes) {
    resize_on_huge_pages(img.bytes, size_t(values));
    read(ImageCodecs::Samples::Uint8, img.bytes.data());
    img.srgb = space == ColorSpace::Srgb;
    return img;
  }
  if (as_halves || as_words) {
    std::vector<uint16_t>& codes = as_halves ? img.halves : img.words;
    resize_on_huge_pages(codes, size_t(values));
    read(as_halves ? ImageCodecs::Samples::Half : ImageCodecs::Samples::Uint16, codes.data());
    return img;
  }
  resize_on_huge_pages(img.texels, size_t(values));
  read(ImageCodecs::Samples::Float, img.texels.data());
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
                       const std::string& element, TexelStorage storage) {
  if (size == 0) throw InputError(file, element, "image has no data");
  std::string error;
  const auto open = [&] { return image_codecs().open_memory(data, size, error); };
  const std::unique_ptr<ImageCodecs::Input> in = open();
  if (!in) throw InputError(file, element, "cannot decode image: " + error);
  return read_from(*in, open, space, storage, file, element);
}

ImageDesc read_image_file(const std::string& path, ColorSpace space, TexelStorage storage) {
  std::string error;
  const auto open = [&] { return image_codecs().open_file(path, error); };
  const std::unique_ptr<ImageCodecs::Input> in = open();
  if (!in) throw InputError(path, "", "cannot read image: " + error);
  ImageDesc img = read_from(*in, open, space, storage, path, "");
  img.name = path;
  return img;
}

}  // namespace prism
