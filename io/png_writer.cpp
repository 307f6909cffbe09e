#include "io/png_writer.h"

#include <algorithm>
#include <cmath>

#include "io/atomic_file.h"
#include "io/errors.h"
#include "io/image_codecs.h"

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

  const ImageCodecs& codecs = image_codecs();
  AtomicFile out(path);
  std::string error;
  if (!codecs.write_png(out.temp_path(), width, height, rgb.data(), error))
    throw OutputError(path, "cannot write PNG: " + error);
  out.commit();
}

}  // namespace prism
