// Accumulation at the extremes: 2^20 samples into one pixel keep the exact mean, whatever the
// order and dynamic range of the samples (the film sums in double); and what reaches a half-float
// file stays finite.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/film.h"
#include "gltf_writer.h"
#include "io/exr_writer.h"
#include "io/image_decode.h"

namespace prism {
namespace {

constexpr uint64_t kSamples = uint64_t(1) << 20;

float pixel_red(const Film& film) {
  float rgba[4];
  film.mean(0, 0, rgba);
  return rgba[0];
}

// v_i = 1 + i 2^-20: every value and every partial sum is exact in double, so the mean must be
// the float nearest 1 + (2^20 - 1) / 2^21.
TEST(AccumulationExtremes, MillionSampleMeanIsExact) {
  Film film(1, 1);
  for (uint64_t i = 0; i < kSamples; ++i) film.add_sample(0, 0, Rgb(1.0f + float(i) * 0x1p-20f), 1.0f);
  EXPECT_EQ(film.sample_count(0, 0), kSamples);
  const double exact = 1.0 + double(kSamples - 1) * 0x1p-21;
  EXPECT_EQ(pixel_red(film), float(exact));
}

// One firefly of 1e8 before a million samples of 1: a float running sum would stop growing at
// 1e8 (its spacing there is 8) and lose every later sample; the double sum keeps them all.
TEST(AccumulationExtremes, FireflyDoesNotSwallowLaterSamples) {
  Film film(1, 1);
  film.add_sample(0, 0, Rgb(1e8f), 1.0f);
  for (uint64_t i = 1; i < kSamples; ++i) film.add_sample(0, 0, Rgb(1.0f), 1.0f);
  const double exact = (1e8 + double(kSamples - 1)) / double(kSamples);
  EXPECT_EQ(pixel_red(film), float(exact));
  // The variance of the mean is that of the exact sample set: (sum x^2 - n mean^2) / (n (n - 1)).
  const double n = double(kSamples);
  const double sum_sq = 1e16 + (n - 1);
  const double variance = (sum_sq - n * exact * exact) / (n - 1) / n;
  EXPECT_NEAR(film.variance_of_mean(0, 0).x, variance, 1e-6 * variance);
}

// Tiny and huge radiance in one pixel (1e-6 and 1e8, alternating): the mean is exact to double
// rounding, and no sample is lost to the other's magnitude.
TEST(AccumulationExtremes, MixedMagnitudesAverageExactly) {
  Film film(1, 1);
  for (uint64_t i = 0; i < kSamples; ++i) film.add_sample(0, 0, Rgb(i % 2 ? 1e8f : 1e-6f), 1.0f);
  const double exact = (double(1e8f) + double(1e-6f)) / 2.0;
  EXPECT_EQ(pixel_red(film), float(exact));
}

// A half holds at most 65504; OpenEXR's conversion turns anything larger into Inf. Half output
// clamps finite values beyond it to +-65504 and counts them (the renderer warns), and writes
// non-finite ones as 0 (NaN) or +-65504 (Inf); values within range keep half precision (2^-11).
TEST(AccumulationExtremes, HalfOutputClampsTo65504AndNeverWritesInf) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> values = {0.5f,  1e-3f,   65504.0f, 65519.0f, 65520.0f, 1e5f, 1e30f,
                                     -1e6f, -65505.0f, inf,      -inf,     std::nanf(""), 3.0e4f, 1.0f};
  const std::string path = test::make_temp_dir("half") + "/half.exr";
  const ExrWriteReport report = write_exr(path, 1, int(values.size() / 4) + 1, [&] {
    std::vector<float> rgba = values;
    rgba.resize((values.size() / 4 + 1) * 4, 0.25f);
    return rgba;
  }(), {}, ExrPixelType::Half);
  EXPECT_EQ(report.clamped, 6);    // 65519, 65520, 1e5, 1e30, -1e6, -65505
  EXPECT_EQ(report.nonfinite, 3);  // inf, -inf, NaN
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
  in.reset();
  const ImageDesc img = read_image_file(path, ColorSpace::Linear);
  for (size_t i = 0; i < values.size(); ++i) {
    const float v = values[i], got = img.texels[i];
    ASSERT_TRUE(std::isfinite(got)) << i;
    EXPECT_LE(std::abs(got), kHalfMax) << i;
    if (std::isnan(v)) EXPECT_EQ(got, 0.0f);
    else if (std::abs(v) > kHalfMax) EXPECT_EQ(got, std::copysign(kHalfMax, v)) << i;
    else EXPECT_NEAR(got, v, std::abs(v) * 0x1p-11f) << i;
  }
}

}  // namespace
}  // namespace prism
