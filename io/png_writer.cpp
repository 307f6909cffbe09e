#include "io/png_writer.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "io/atomic_file.h"
#include "io/errors.h"

namespace prism {

float linear_to_srgb(float v) {
  if (!(v > 0.0f)) return 0.0f;
  if (v >= 1.0f) return 1.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

void write_png_preview(const std::string& path, int width, int height, const std::vector<float>& rgba) {
  if (rgba.size() != size_t(width) * height * 4) throw OutputError(path, "pixel buffer does not match the image size");
  std::vector<unsigned char> rgb(size_t(width) * height * 3);
  for (size_t i = 0, n = size_t(width) * height; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      rgb[i * 3 + c] = static_cast<unsigned char>(std::lround(linear_to_srgb(rgba[i * 4 + c]) * 255.0f));

  AtomicFile out(path);
  // The writer is chosen by format name: the temporary file's name has no .png ending.
  auto writer = OIIO::ImageOutput::create("png");
  if (!writer) throw OutputError(path, "no PNG writer: " + OIIO::geterror());
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!writer->open(out.temp_path(), spec) || !writer->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
      !writer->close())
    throw OutputError(path, "cannot write PNG: " + writer->geterror());
  out.commit();
}

}  // namespace prism
