// EXR and PNG output: values round-trip, nothing non-finite is written, writes are atomic.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "gltf_writer.h"
#include "io/errors.h"
#include "io/exr_writer.h"
#include "io/image_decode.h"
#include "io/png_writer.h"

namespace prism {
namespace {

namespace fs = std::filesystem;

size_t files_in(const std::string& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(ExrWriter, RoundTripsFloatRgbaAndAttributes) {
  const std::string dir = test::make_temp_dir("exr");
  std::vector<float> px = {0.25f, 1e6f, 3e-8f, 1.0f, 0.0f, 2.5f, 7.0f, 0.5f};
  const ExrWriteReport report = write_exr(dir + "/a.exr", 2, 1, px, {{"prism/spp", 64}, {"prism/integrator", std::string("path")}});
  EXPECT_EQ(report.nonfinite, 0);
  EXPECT_EQ(report.clamped, 0);  // 1e6 is nothing to a float
  EXPECT_EQ(files_in(dir), 1u);  // no temporary file left behind
  const ImageDesc img = read_image_file(dir + "/a.exr", ColorSpace::Linear);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.channels, 4);
  for (size_t i = 0; i < px.size(); ++i) EXPECT_EQ(img.texels[i], px[i]) << i;
  auto in = OIIO::ImageInput::open(dir + "/a.exr");
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_int_attribute("prism/spp"), 64);
  EXPECT_EQ(in->spec().get_string_attribute("prism/integrator"), "path");
}

TEST(ExrWriter, NonFiniteValuesNeverReachTheFile) {
  const std::string dir = test::make_temp_dir("exr");
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> px = {std::nanf(""), inf, -inf, 1.0f};
  EXPECT_EQ(write_exr(dir + "/b.exr", 1, 1, px, {}).nonfinite, 3);
  const ImageDesc img = read_image_file(dir + "/b.exr", ColorSpace::Linear);
  for (float v : img.texels) EXPECT_TRUE(std::isfinite(v));
  EXPECT_EQ(img.texels[0], 0.0f);
  EXPECT_EQ(img.texels[1], std::numeric_limits<float>::max());
}

TEST(ExrWriter, UnwritableTargetsFailCleanlyAndKeepEarlierOutput) {
  const std::string dir = test::make_temp_dir("exr");
  const std::vector<float> px(4, 0.5f);
  EXPECT_THROW(write_exr(dir + "/missing/x.exr", 1, 1, px, {}), OutputError);
  fs::create_directory(dir + "/is_a_dir.exr");
  EXPECT_THROW(write_exr(dir + "/is_a_dir.exr", 1, 1, px, {}), OutputError);
  // A failed write leaves an earlier image in place: the temporary file is never renamed.
  write_exr(dir + "/keep.exr", 1, 1, px, {});
  const auto size = fs::file_size(dir + "/keep.exr");
  EXPECT_THROW(write_exr(dir + "/keep.exr", 2, 2, px, {}), OutputError);  // buffer size mismatch
  EXPECT_EQ(fs::file_size(dir + "/keep.exr"), size);
  EXPECT_EQ(files_in(dir), 2u);
}

TEST(PngWriter, EncodesSrgb) {
  EXPECT_FLOAT_EQ(linear_to_srgb(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
  EXPECT_NEAR(linear_to_srgb(0.18f), 0.46135f, 1e-4f);
  EXPECT_FLOAT_EQ(linear_to_srgb(std::nanf("")), 0.0f);
  for (float v : {0.001f, 0.01f, 0.2f, 0.7f}) EXPECT_NEAR(srgb_to_linear(linear_to_srgb(v)), v, 1e-6f);
  const std::string dir = test::make_temp_dir("png");
  write_png_preview(dir + "/p.png", 2, 1, {0.18f, 0.0f, 5.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f});
  auto in = OIIO::ImageInput::open(dir + "/p.png");
  ASSERT_TRUE(in);
  std::vector<unsigned char> rgb(6);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  EXPECT_EQ(rgb[0], 118);  // round(0.46135 * 255)
  EXPECT_EQ(rgb[1], 0);
  EXPECT_EQ(rgb[2], 255);  // clipped
  EXPECT_EQ(files_in(dir), 1u);
}

}  // namespace
}  // namespace prism
