// MIP levels and footprint lookups: block means, codes, the level a footprint reads, ray cones.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/camera.h"
#include "core/mip_levels.h"
#include "core/pcg32.h"
#include "core/scene.h"
#include "materials/texture_lookup.h"
#include "scene_builders.h"

namespace prism {
namespace {

ImageDesc float_image(int width, int height, int channels, const std::vector<float>& values) {
  ImageDesc img;
  img.name = "test";
  img.width = width;
  img.height = height;
  img.channels = channels;
  img.texels = values;
  return img;
}

TEST(MipLevels, BlockMeansDownToOneTexel) {
  ImageDesc img = float_image(4, 2, 1, {1, 3, 5, 7, 2, 4, 6, 8});
  build_mip_levels(img);
  ASSERT_EQ(img.mips.size(), 2u);
  ASSERT_EQ(img.mips[0].width, 2);
  ASSERT_EQ(img.mips[0].height, 1);
  EXPECT_EQ(img.mips[0].texel(0, 0).rgb.x, 2.5f);  // (1 + 3 + 2 + 4) / 4
  EXPECT_EQ(img.mips[0].texel(1, 0).rgb.x, 6.5f);
  ASSERT_EQ(img.mips[1].width, 1);
  EXPECT_EQ(img.mips[1].texel(0, 0).rgb.x, 4.5f);
  EXPECT_EQ(&img.level(0), &img);
  EXPECT_EQ(&img.level(7), &img.mips.back());  // past the coarsest: the coarsest
}

TEST(MipLevels, OddSizesTakeThreeTexelsAtTheEnd) {
  ImageDesc img = float_image(3, 3, 1, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  build_mip_levels(img);
  ASSERT_EQ(img.mips.size(), 1u);
  EXPECT_EQ(img.mips[0].texel(0, 0).rgb.x, 5.0f);
  ImageDesc row = float_image(5, 1, 1, {1, 2, 3, 4, 5});
  build_mip_levels(row);
  ASSERT_EQ(row.mips[0].width, 2);
  EXPECT_EQ(row.mips[0].texel(0, 0).rgb.x, 1.5f);
  EXPECT_EQ(row.mips[0].texel(1, 0).rgb.x, 4.0f);  // (3 + 4 + 5) / 3
  ImageDesc one = float_image(1, 1, 1, {1});
  build_mip_levels(one);
  EXPECT_TRUE(one.mips.empty());
}

TEST(MipLevels, NearestCodeIsTheNearestDecodedValue) {
  Pcg32 rng(7, 0);
  for (const auto* table : {&kSrgbCodes, &kLinearCodes})
    for (int i = 0; i < 20000; ++i) {
      const float v = i < 256 ? (*table)[size_t(i)] : rng.next_float() * 1.1f - 0.05f;
      const int c = nearest_code(*table, v);
      for (int other = 0; other < 256; ++other)
        ASSERT_LE(std::abs((*table)[size_t(c)] - v), std::abs((*table)[size_t(other)] - v)) << v;
    }
}

// Levels of 8-bit images are codes again: each the nearest code to the mean of the decoded block,
// colour through sRGB and alpha linear.
TEST(MipLevels, ByteLevelsHoldTheNearestCodeOfTheBlockMean) {
  ImageDesc img;
  img.width = 64;
  img.height = 32;
  img.channels = 4;
  img.srgb = true;
  Pcg32 rng(3, 0);
  for (int i = 0; i < 64 * 32 * 4; ++i) img.bytes.push_back(uint8_t(rng.next_u32() & 255));
  build_mip_levels(img);
  ASSERT_EQ(img.mips.size(), 6u);  // 32x16 ... 1x1
  const ImageDesc& first = img.mips[0];
  ASSERT_TRUE(first.holds_bytes());
  for (int y = 0; y < first.height; ++y)
    for (int x = 0; x < first.width; ++x) {
      float sum[4] = {};
      for (int sy = 2 * y; sy < 2 * y + 2; ++sy)
        for (int sx = 2 * x; sx < 2 * x + 2; ++sx) {
          const Rgba t = img.texel(sx, sy);
          sum[0] += t.rgb.x, sum[1] += t.rgb.y, sum[2] += t.rgb.z, sum[3] += t.a;
        }
      const size_t i = (size_t(y) * 32 + size_t(x)) * 4;
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(first.bytes[i + size_t(c)], nearest_code(c < 3 ? kSrgbCodes : kLinearCodes, sum[c] / 4))
            << x << "," << y << " channel " << c;
    }
  // The last level is the whole image's mean. Each of the six levels rounds its texels to the
  // nearest linear alpha code, moving a mean of them by at most half a step: 3 steps in all.
  double mean = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) mean += img.texel(x, y).a;
  EXPECT_NEAR(img.mips.back().texel(0, 0).a, mean / (64 * 32), 6 * 0.5 / 255);
}

// An 8x8 grey float texture (repeat) in a scene of its own, with MIP levels.
struct MippedTexture {
  SceneDesc scene;
  TextureRef ref;
  MippedTexture() {
    std::vector<float> v;
    Pcg32 rng(11, 0);
    for (int i = 0; i < 64; ++i) v.push_back(rng.next_float());
    scene.images.push_back(float_image(8, 8, 1, v));
    build_mip_levels(scene.images[0]);
    TextureDesc tex;
    tex.image = 0;
    scene.textures.push_back(tex);
    ref.texture = 0;
  }
  // A bilinear lookup of level `level` alone.
  float level(int level, Vec2 uv) const {
    SceneDesc one;
    one.images.push_back(scene.images[0].level(level));
    one.images[0].mips.clear();
    one.textures = scene.textures;
    return lookup_texture(one, ref, uv).rgb.x;
  }
  float lookup(Vec2 uv, float width) const { return lookup_texture(scene, ref, uv, width).rgb.x; }
};

TEST(TextureFootprint, LevelsFollowTheTexelsAFootprintSpans) {
  const MippedTexture t;
  for (const Vec2 uv : {Vec2{0.3f, 0.7f}, Vec2{0.05f, 0.95f}, Vec2{0.61f, 0.12f}}) {
    EXPECT_EQ(t.lookup(uv, 0), t.level(0, uv));  // a point: the full-size image
    EXPECT_EQ(t.lookup(uv, 1.0f / 8), t.level(0, uv));  // one texel wide: still level 0
    EXPECT_EQ(t.lookup(uv, 0.5f / 8), t.level(0, uv));  // under one texel
    EXPECT_EQ(t.lookup(uv, 2.0f / 8), t.level(1, uv));  // two texels: level 1 alone
    EXPECT_EQ(t.lookup(uv, 4.0f / 8), t.level(2, uv));
    // Between: one of the two levels, the coarser with probability frac(log2 of the width in
    // texels), chosen by a hash of uv (stochastic trilinear filtering).
    const float a = t.level(1, uv), b = t.level(2, uv), v = t.lookup(uv, 3.0f / 8);
    EXPECT_TRUE(v == a || v == b) << v;
    // Wider than the image: its mean, the 1x1 level.
    EXPECT_EQ(t.lookup(uv, 100.0f), t.level(3, uv));
  }
  EXPECT_EQ(t.scene.images[0].mips.back().width, 1);
}

// The coarser level is read with probability frac(lambda), so lookups blend the two levels in
// expectation. 4000 uniform uvs: the count of coarser reads is binomial, and 4 standard
// deviations bound it.
TEST(TextureFootprint, StochasticLevelsBlendInExpectation) {
  const MippedTexture t;
  const float w = std::log2(3.0f) - 1;  // a footprint 3 texels wide: between levels 1 and 2
  Pcg32 rng(5, 0);
  int coarse = 0, n = 0;
  while (n < 4000) {
    const Vec2 uv{rng.next_float(), rng.next_float()};
    const float a = t.level(1, uv), b = t.level(2, uv);
    if (a == b) continue;  // either level: no evidence
    ++n;
    coarse += t.lookup(uv, 3.0f / 8) == b;
  }
  const double sigma = std::sqrt(n * w * (1 - w));
  EXPECT_NEAR(coarse, n * w, 4 * sigma);
}

TEST(TextureFootprint, TextureTransformScalesTheFootprint) {
  MippedTexture t;
  const Vec2 uv{0.2f, 0.4f};
  const float direct = t.lookup({0.4f, 0.8f}, 4.0f / 8);
  t.ref.transform = {2, 0, 0, 0, 2, 0};  // uv x 2: the footprint spans twice the texels
  EXPECT_EQ(t.lookup(uv, 2.0f / 8), direct);
}

TEST(RayCones, CameraRaysSpanTheirPixel) {
  CameraDesc d;
  d.yfov = 1.0f;
  const Camera cam(d, 200, 100);
  const Ray centre = cam.generate_ray(100, 50);
  EXPECT_EQ(centre.cone_width, 0.0f);
  EXPECT_NEAR(centre.cone_spread, 2 * std::tan(0.5f) / 100, 1e-7f);
  EXPECT_NEAR(centre.cone_width_at(10), 10 * centre.cone_spread, 1e-6f);
  CameraDesc o;
  o.projection = Projection::Orthographic;
  o.ymag = 2;
  const Ray ortho = Camera(o, 200, 100).generate_ray(0, 0);
  EXPECT_EQ(ortho.cone_spread, 0.0f);
  EXPECT_NEAR(ortho.cone_width_at(1000), 4.0f / 100, 1e-7f);
}

TEST(RayCones, HitsKnowTheirUvPerLength) {
  SceneDesc desc;
  const int m = test::add_material(desc, Rgb(0.5f));
  desc.images.push_back(float_image(2, 2, 1, {1, 1, 1, 1}));
  build_mip_levels(desc.images[0]);  // without levels, hits need no footprint and get none
  desc.textures.push_back(TextureDesc{});
  desc.textures[0].image = 0;
  desc.materials[size_t(m)].base_color_texture.texture = 0;
  // A 2 x 4 quad with uv running over [0,1]^2: sqrt(uv area / area) = sqrt(1 / 8).
  test::add_quad(desc, Vec3(-1, -2, 0), Vec3(2, 0, 0), Vec3(0, 4, 0), m);
  const Scene scene(std::move(desc));
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(Ray(Vec3(0.3f, 0.2f, 5), Vec3(0, 0, -1)), hit));
  EXPECT_NEAR(hit.uv_per_length, std::sqrt(1.0f / 8), 1e-6f);
  hit.cone_width = 0.5f;
  EXPECT_NEAR(hit.uv_width(), 0.5f * std::sqrt(1.0f / 8), 1e-6f);
}

}  // namespace
}  // namespace prism
