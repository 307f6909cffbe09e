#include "core/image_desc.h"

#include <cmath>

namespace prism {

float srgb_to_linear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

namespace {

std::array<float, 256> code_table(bool srgb) {
  std::array<float, 256> t{};
  constexpr float kScale = 1.0f / 255.0f;  // OpenImageIO's uint8 -> float: code x (1 / 255)
  for (int i = 0; i < 256; ++i) t[i] = srgb ? srgb_to_linear(float(i) * kScale) : float(i) * kScale;
  return t;
}

}  // namespace

const std::array<float, 256> kSrgbCodes = code_table(true);
const std::array<float, 256> kLinearCodes = code_table(false);

}  // namespace prism
