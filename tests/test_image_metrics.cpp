// Image metrics: the luminance's relative error per pixel, the measure the noise target bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/image_metrics.h"

namespace prism {
namespace {

// A grey RGB image of one row.
ImageDesc grey_row(const std::vector<float>& values) {
  ImageDesc img;
  img.width = int(values.size());
  img.height = 1;
  img.channels = 3;
  for (float v : values) img.texels.insert(img.texels.end(), {v, v, v});
  return img;
}

// Reference luminances 1, 2, 0, 1 (mean 1, so a floor of 0.01): errors 0.1, 0.1, 0.005 / 0.01 and 0.
TEST(ImageMetrics, RelativeErrorIsTheNoiseTargetsMeasure) {
  const ImageComparison c = compare_images(grey_row({1.1f, 1.8f, 0.005f, 1.0f}), grey_row({1, 2, 0, 1}));
  EXPECT_NEAR(c.relative_error_rms, std::sqrt((0.01 + 0.01 + 0.25 + 0) / 4), 1e-6);
  EXPECT_NEAR(c.relative_error_median, 0.1, 1e-6);  // the upper median of 0, 0.1, 0.1, 0.5

  // A non-finite pixel is left out, of the floor's mean too.
  const float inf = std::numeric_limits<float>::infinity();
  const ImageComparison d = compare_images(grey_row({1.1f, inf}), grey_row({1, 3}));
  EXPECT_EQ(d.pixels, 1u);
  EXPECT_NEAR(d.relative_error_rms, 0.1, 1e-6);
}

}  // namespace
}  // namespace prism
