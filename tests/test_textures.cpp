// Textures: sRGB decoding from a glTF image, bilinear lookup and the glTF wrap modes.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

#include "gltf_writer.h"
#include "io/gltf_loader.h"
#include "core/rgbe.h"
#include "io/image_decode.h"
#include "materials/material_eval.h"
#include "materials/texture_lookup.h"

namespace prism {
namespace {

// Writes `pixels` (samples of `type`, laid out as `spec` says) as the image file at `path`.
::testing::AssertionResult write_image(const std::string& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                                       const void* pixels) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec) || !out->write_image(type, pixels) || !out->close())
    return ::testing::AssertionFailure() << "cannot write " << path;
  return ::testing::AssertionSuccess();
}

std::vector<unsigned char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Whether two images read the same texels, bit for bit.
bool same_texels(const ImageDesc& a, const ImageDesc& b) {
  if (a.width != b.width || a.height != b.height) return false;
  const auto bits = [](float v) { return std::bit_cast<uint32_t>(v); };
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const Rgba p = a.texel(x, y), q = b.texel(x, y);
      for (int c = 0; c < 3; ++c)
        if (bits(p.rgb[c]) != bits(q.rgb[c])) return false;
      if (bits(p.a) != bits(q.a)) return false;
    }
  return true;
}

TEST(WrapTexel, GltfWrapModes) {
  EXPECT_EQ(wrap_texel(-1, 4, WrapMode::Repeat), 3);
  EXPECT_EQ(wrap_texel(5, 4, WrapMode::Repeat), 1);
  EXPECT_EQ(wrap_texel(-3, 4, WrapMode::ClampToEdge), 0);
  EXPECT_EQ(wrap_texel(9, 4, WrapMode::ClampToEdge), 3);
  EXPECT_EQ(wrap_texel(4, 4, WrapMode::MirroredRepeat), 3);
  EXPECT_EQ(wrap_texel(-1, 4, WrapMode::MirroredRepeat), 0);
  EXPECT_EQ(wrap_texel(8, 4, WrapMode::MirroredRepeat), 0);
}

// The wrap of every texel coordinate near and far from the image, for widths that are powers of
// two (wrapped by a mask) and others, against glTF's definitions written with 64-bit floor modulo.
TEST(WrapTexel, EveryCoordinateMatchesTheDefinitions) {
  const auto floor_mod = [](int64_t i, int64_t n) { return ((i % n) + n) % n; };
  int mismatches = 0;
  for (int n : {1, 2, 3, 4, 5, 7, 8, 1000, 1024, 2048, 4097}) {
    std::vector<int> coordinates = {-1000000000, 1000000000, 999999999, -999999999};
    for (int i = -3 * n - 2; i <= 3 * n + 2; ++i) coordinates.push_back(i);
    for (int i : coordinates) {
      const int64_t mirrored = floor_mod(i, 2 * int64_t(n));
      mismatches += wrap_texel(i, n, WrapMode::Repeat) != floor_mod(i, n);
      mismatches += wrap_texel(i, n, WrapMode::MirroredRepeat) != (mirrored < n ? mirrored : 2 * n - 1 - mirrored);
      mismatches += wrap_texel(i, n, WrapMode::ClampToEdge) != std::clamp(i, 0, n - 1);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// A bilinear or nearest lookup reads the texels and weights glTF's definitions give, written with
// std::floor: at coordinates of every magnitude and sign (texel edges, -0, between texels, far
// enough out that floats hold no fraction, and past int's range), for every wrap mode, on an
// image whose width is a power of two and one whose width is not.
TEST(Textures, LookupsReadTheTexelsTheirCoordinatesFloorTo) {
  const float coordinates[] = {-1e12f, -3e9f, -1e9f, -2e7f - 0.5f, -12345.678f, -1.0f, -0.5f, -1e-8f, -0.0f, 0.0f,
                               1e-8f,  0.124f, 0.375f, 0.5f, 0x1.fffffep-1f, 1.0f, 7.25f, 1e7f + 0.5f, 3e9f, 1e12f};
  int compared = 0;
  for (int width : {4, 3}) {
    SceneDesc scene;
    ImageDesc& img = scene.images.emplace_back();
    img.width = width;
    img.height = 2;
    img.channels = 1;
    for (int i = 0; i < width * 2; ++i) img.texels.push_back(float(1 << i));  // every texel its own bit
    for (WrapMode mode : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge})
      for (bool nearest : {false, true}) {
        scene.textures.push_back({.image = 0, .wrap_s = mode, .wrap_t = mode, .nearest = nearest});
        const TextureRef ref{.texture = int(scene.textures.size()) - 1};
        for (float u : coordinates)
          for (float v : coordinates) {
            const float x = u * float(img.width) - 0.5f, y = v * float(img.height) - 0.5f;
            const auto floored = [](float c) { return int(std::clamp(std::floor(c), -1e9f, 1e9f)); };
            float expected;
            if (nearest) {
              expected = img.texel(wrap_texel(floored(x + 0.5f), img.width, mode),
                                   wrap_texel(floored(y + 0.5f), img.height, mode)).rgb.x;
            } else {
              const int x0 = floored(x), y0 = floored(y);
              const float fx = x - std::floor(x), fy = y - std::floor(y);
              const int xa = wrap_texel(x0, img.width, mode), xb = wrap_texel(x0 + 1, img.width, mode);
              const int ya = wrap_texel(y0, img.height, mode), yb = wrap_texel(y0 + 1, img.height, mode);
              expected = img.texel(xa, ya).rgb.x * ((1 - fx) * (1 - fy)) + img.texel(xb, ya).rgb.x * (fx * (1 - fy)) +
                         img.texel(xa, yb).rgb.x * ((1 - fx) * fy) + img.texel(xb, yb).rgb.x * (fx * fy);
            }
            const Rgba got = lookup_texture(scene, ref, {u, v}, 0.0f);
            ASSERT_EQ(got.rgb.x, expected) << "width " << width << ", mode " << int(mode) << ", nearest " << nearest
                                           << ", uv " << u << " " << v;
            ++compared;
          }
      }
  }
  EXPECT_EQ(compared, 2 * 3 * 2 * 20 * 20);
}

TEST(Textures, BaseColourTextureIsDecodedFromSrgbAndLookedUp) {
  const std::string dir = test::make_temp_dir("tex");
  // A 2x1 PNG: left texel sRGB (255, 128, 0), right texel (0, 64, 255).
  const unsigned char pixels[] = {255, 128, 0, 0, 64, 255};
  {
    auto out = OIIO::ImageOutput::create(dir + "/t.png");
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(dir + "/t.png", OIIO::ImageSpec(2, 1, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels));
    out->close();
  }
  test::GltfWriter w;
  w.doc()["images"] = nlohmann::json::array({{{"uri", "t.png"}}});
  w.doc()["samplers"] = nlohmann::json::array({{{"magFilter", 9728}, {"wrapS", 33071}}});  // NEAREST, CLAMP
  w.doc()["textures"] = nlohmann::json::array({{{"source", 0}}, {{"source", 0}, {"sampler", 0}}});
  w.doc()["materials"] = nlohmann::json::array(
      {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {1, 1, 0.5, 1}}}}},
       {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}});
  const std::vector<float> tri = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const int pos = w.add_positions(tri);
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos, -1, 0)}}), w.add_node({{"mesh", w.add_mesh(pos, -1, 1)}})});
  Diagnostics diag;
  const SceneDesc s = load_gltf(w.write(dir, "scene"), diag);
  ASSERT_EQ(s.images.size(), 1u);  // one image, decoded once for its colour space
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_TRUE(s.features().textures);
  EXPECT_TRUE(s.images[0].holds_bytes());  // an 8-bit PNG keeps its codes
  EXPECT_TRUE(s.images[0].srgb);
  EXPECT_NEAR(s.images[0].texel(0, 0).rgb.y, srgb_to_linear(128.0f / 255.0f), 1e-6f);

  // At a texel centre the bilinear value is the texel; the factor multiplies it.
  const Rgb left = base_color(s, s.materials[0], {0.25f, 0.5f});
  EXPECT_NEAR(left.x, 1.0f, 1e-6f);
  EXPECT_NEAR(left.y, srgb_to_linear(128.0f / 255.0f), 1e-6f);
  // Halfway between the two texel centres: the average of both (repeat wrap).
  const Rgb mid = base_color(s, s.materials[0], {0.5f, 0.5f});
  EXPECT_NEAR(mid.z, 0.5f * 0.5f * 1.0f, 1e-6f);
  // u = 0 lies between the last texel (wrapped) and the first.
  const Rgb edge = base_color(s, s.materials[0], {0.0f, 0.5f});
  EXPECT_NEAR(edge.x, 0.5f, 1e-6f);
  // Nearest filtering with clamping: far outside on the right stays the right texel.
  const Rgb clamped = base_color(s, s.materials[1], {7.0f, 0.5f});
  EXPECT_NEAR(clamped.z, 1.0f, 1e-6f);
  EXPECT_NEAR(clamped.x, 0.0f, 1e-6f);
}

// An 8-bit image kept as its codes reads exactly what decoding it to floats gives, texel for
// texel, in both colour spaces and for every channel layout: keeping the bytes only saves memory.
TEST(Textures, EightBitTexelsKeptAsBytesReadAsTheirFloatDecoding) {
  const std::string dir = test::make_temp_dir("texbytes");
  for (int channels : {1, 2, 3, 4}) {
    // 64 x 4 texels whose values run through all 256 codes in every channel, shifted per channel.
    const int width = 64, height = 4;
    std::vector<unsigned char> pixels(size_t(width) * height * channels);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>((i / channels + 37 * (i % channels)) % 256);
    const std::string path = dir + "/c" + std::to_string(channels) + ".png";
    ASSERT_TRUE(write_image(path, OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8),
                            OIIO::TypeDesc::UINT8, pixels.data()));
    const std::vector<unsigned char> png = file_bytes(path);
    for (ColorSpace space : {ColorSpace::Srgb, ColorSpace::Linear}) {
      const ImageDesc bytes = decode_image(png.data(), png.size(), space, path, "image", TexelStorage::Compact);
      const ImageDesc floats = decode_image(png.data(), png.size(), space, path, "image", TexelStorage::Float);
      ASSERT_TRUE(bytes.holds_bytes());
      ASSERT_FALSE(floats.holds_bytes());
      EXPECT_EQ(bytes.memory_bytes() * sizeof(float), floats.memory_bytes());
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const Rgba a = bytes.texel(x, y), b = floats.texel(x, y);
          ASSERT_EQ(a.rgb.x, b.rgb.x) << channels << " channels, texel " << x << "," << y;
          ASSERT_EQ(a.rgb.y, b.rgb.y) << channels << " channels, texel " << x << "," << y;
          ASSERT_EQ(a.rgb.z, b.rgb.z) << channels << " channels, texel " << x << "," << y;
          ASSERT_EQ(a.a, b.a) << channels << " channels, texel " << x << "," << y;
        }
    }
  }
}

// Every one of the 65536 halves reads as the float it stands for (IEEE 754 binary16: sign,
// 5 exponent bits biased by 15, 10 mantissa bits; exponent 0 subnormal, 31 infinity and NaN).
TEST(Textures, HalfToFloatIsExactForEveryHalf) {
  for (uint32_t h = 0; h < 0x10000u; ++h) {
    const int exponent = int(h >> 10) & 0x1f, mantissa = int(h & 0x3ffu);
    const float sign = (h & 0x8000u) ? -1.0f : 1.0f;
    const float got = half_to_float(uint16_t(h));
    if (exponent == 31) {
      if (mantissa == 0)
        ASSERT_EQ(got, sign * INFINITY) << h;
      else
        ASSERT_TRUE(std::isnan(got)) << h;
      continue;
    }
    const float expected = exponent == 0 ? sign * std::ldexp(float(mantissa), -24)
                                         : sign * std::ldexp(float(1024 + mantissa), exponent - 25);
    ASSERT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(expected)) << h;
  }
}

// A half-float EXR kept as its halves reads exactly what decoding it to floats gives, for every
// channel layout; one whose channels are not all half (half colour, float alpha) is kept as floats.
TEST(Textures, HalfTexelsKeptAsHalvesReadAsTheirFloatDecoding) {
  const std::string dir = test::make_temp_dir("texhalves");
  const std::vector<float> values = {0.0f, 1e-6f, 6.1e-5f, 0.25f, 0.5f, 1.0f, 3.14159f, 1000.0f, 60000.0f, 0.1f, 7.0f};
  const auto write = [&](const std::string& path, const OIIO::ImageSpec& spec) {
    std::vector<float> pixels(size_t(spec.width) * spec.height * spec.nchannels);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = values[(i * 7 + i / 3) % values.size()];
    return write_image(path, spec, OIIO::TypeDesc::FLOAT, pixels.data());
  };
  const int width = 16, height = 3;
  for (int channels : {1, 2, 3, 4}) {
    const std::string path = dir + "/h" + std::to_string(channels) + ".exr";
    ASSERT_TRUE(write(path, OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::HALF)));
    const std::vector<unsigned char> exr = file_bytes(path);
    const ImageDesc halves = decode_image(exr.data(), exr.size(), ColorSpace::Auto, path, "image", TexelStorage::Compact);
    const ImageDesc floats = decode_image(exr.data(), exr.size(), ColorSpace::Auto, path, "image", TexelStorage::Float);
    ASSERT_TRUE(halves.holds_halves()) << channels;
    ASSERT_FALSE(floats.holds_halves());
    EXPECT_EQ(halves.memory_bytes() * 2, floats.memory_bytes());
    EXPECT_TRUE(same_texels(halves, floats)) << channels << " channels";
    const ImageDesc from_file = read_image_file(path, ColorSpace::Linear, TexelStorage::Compact);
    EXPECT_TRUE(from_file.holds_halves());
    EXPECT_TRUE(same_texels(from_file, floats));
  }
  const std::string mixed_path = dir + "/mixed.exr";
  OIIO::ImageSpec mixed(width, height, 4, OIIO::TypeDesc::HALF);
  mixed.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT};
  ASSERT_TRUE(write(mixed_path, mixed));
  const ImageDesc compact = read_image_file(mixed_path, ColorSpace::Linear, TexelStorage::Compact);
  EXPECT_FALSE(compact.holds_halves());
  EXPECT_TRUE(same_texels(compact, read_image_file(mixed_path, ColorSpace::Linear)));
}

// A linear 16-bit PNG (a normal map) kept as its codes reads exactly what decoding it to floats
// gives, for every one of the 65536 codes and every channel layout; an sRGB one is kept as floats.
TEST(Textures, SixteenBitLinearTexelsKeptAsCodesReadAsTheirFloatDecoding) {
  const std::string dir = test::make_temp_dir("texwords");
  const int width = 256, height = 256;  // 65536 texels: every code in every channel, shifted per channel
  for (int channels : {1, 2, 3, 4}) {
    std::vector<uint16_t> pixels(size_t(width) * height * channels);
    for (size_t i = 0; i < pixels.size(); ++i)
      pixels[i] = static_cast<uint16_t>((i / channels + 12345 * (i % channels)) % 65536);
    const std::string path = dir + "/w" + std::to_string(channels) + ".png";
    ASSERT_TRUE(write_image(path, OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT16),
                            OIIO::TypeDesc::UINT16, pixels.data()));
    const std::vector<unsigned char> png = file_bytes(path);
    const ImageDesc words = decode_image(png.data(), png.size(), ColorSpace::Linear, path, "image", TexelStorage::Compact);
    const ImageDesc floats = decode_image(png.data(), png.size(), ColorSpace::Linear, path, "image", TexelStorage::Float);
    ASSERT_TRUE(words.holds_words());
    EXPECT_EQ(words.memory_bytes() * 2, floats.memory_bytes());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Rgba a = words.texel(x, y), b = floats.texel(x, y);
        ASSERT_TRUE(a.rgb == b.rgb && a.a == b.a) << channels << " channels, texel " << x << "," << y;
      }
    const ImageDesc srgb = decode_image(png.data(), png.size(), ColorSpace::Srgb, path, "image", TexelStorage::Compact);
    EXPECT_FALSE(srgb.holds_words());
    EXPECT_FALSE(srgb.texels.empty());
  }
}

TEST(Textures, KhrTextureTransformOffsetRotationScale) {
  const std::string dir = test::make_temp_dir("textransform");
  // A 2x2 PNG: top-left red, top-right green, bottom-left blue, bottom-right white.
  const unsigned char pixels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  {
    auto out = OIIO::ImageOutput::create(dir + "/q.png");
    ASSERT_TRUE(out->open(dir + "/q.png", OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels));
    out->close();
  }
  test::GltfWriter w;
  w.doc()["extensionsUsed"] = {"KHR_texture_transform"};
  w.doc()["images"] = nlohmann::json::array({{{"uri", "q.png"}}});
  w.doc()["samplers"] = nlohmann::json::array({{{"magFilter", 9728}}});  // nearest
  w.doc()["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
  const double half_pi = 1.5707963267948966;
  w.doc()["materials"] = nlohmann::json::array(
      {{{"pbrMetallicRoughness",
         {{"baseColorTexture",
           {{"index", 0},
            {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"rotation", half_pi}, {"scale", {1, 0.5}}}}}}}}}}}});
  const int pos = w.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  w.set_scene_nodes({w.add_node({{"mesh", w.add_mesh(pos, -1, 0)}})});
  Diagnostics diag;
  const SceneDesc s = load_gltf(w.write(dir, "scene"), diag);
  EXPECT_FALSE(diag.contains("KHR_texture_transform"));
  // uv' = T R S uv with R = [cos sin; -sin cos]: (0.1, 0.9) -> S (0.1, 0.45) -> R (0.45, -0.1)
  // -> T (0.95, -0.1), which wraps to (0.95, 0.9): the bottom-right texel, white.
  const Rgb a = base_color(s, s.materials[0], {0.1f, 0.9f});
  EXPECT_NEAR(a.x, 1.0f, 1e-5f);
  EXPECT_NEAR(a.y, 1.0f, 1e-5f);
  EXPECT_NEAR(a.z, 1.0f, 1e-5f);
  // (0.9, 0.2) -> (0.9, 0.1) -> (0.1, -0.9) -> (0.6, -0.9) wraps to (0.6, 0.1): top-right, green.
  const Rgb b = base_color(s, s.materials[0], {0.9f, 0.2f});
  EXPECT_NEAR(b.x, 0.0f, 1e-5f);
  EXPECT_NEAR(b.y, 1.0f, 1e-5f);
}

// The exponent table is 2^(e - 136), and every texel (every exponent, every mantissa of a channel
// beside others) decodes to a colour that exact_rgbe encodes back to the same colour, bit for bit.
TEST(Rgbe, EveryTexelEncodesBackExactly) {
  EXPECT_EQ(kRgbeScales[0], 0.0f);
  for (int e = 1; e < 256; ++e) EXPECT_EQ(kRgbeScales[size_t(e)], std::ldexp(1.0f, e - 136)) << e;
  int failures = 0;
  for (uint32_t e = 0; e < 256; ++e)
    for (uint32_t r = 0; r < 256; ++r) {
      const RgbeTexel t = r | ((r * 37 + 11) % 256) << 8 | ((r * 101) % 256) << 16 | e << 24;
      const Rgb c = rgbe_to_rgb(t);
      const std::optional<RgbeTexel> back = exact_rgbe(c);
      const auto bits = [](const Rgb& v) { return std::array{std::bit_cast<uint32_t>(v.x), std::bit_cast<uint32_t>(v.y), std::bit_cast<uint32_t>(v.z)}; };
      if (!back || bits(rgbe_to_rgb(*back)) != bits(c)) ++failures;
    }
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(rgbe_to_rgb(0x81'01'40'80u), Rgb(1.0f, 0.5f, 0.0078125f));  // 128, 64, 1 at exponent 129
}

// Colours that no texel decodes to exactly are refused, never rounded.
TEST(Rgbe, ColoursWithoutAnExactTexelAreRefused) {
  for (const Rgb& c : {Rgb(0.1f, 0, 0), Rgb(1.0f, 1.0f / 512, 0), Rgb(-1.0f, 0, 0), Rgb(NAN, 1, 1), Rgb(INFINITY, 0, 0),
                       Rgb(-0.0f, 0, 0), Rgb(0x1p-149f, 0, 0), Rgb(0x1p-136f, 0, 0), Rgb(0x1p127f, 0, 0)})
    EXPECT_FALSE(exact_rgbe(c)) << c.x << " " << c.y << " " << c.z;
  EXPECT_TRUE(exact_rgbe(Rgb(0x1p-135f, 0, 0)));  // the smallest: mantissa 1 at exponent 1
  EXPECT_TRUE(exact_rgbe(Rgb(255 * 0x1p119f, 0, 0)));  // the largest
  EXPECT_EQ(exact_rgbe(Rgb(0.0f)), RgbeTexel(0));
}

// A Radiance .hdr image kept as its RGBE texels reads exactly what decoding it to floats gives, in
// a third of the memory, over more rows than one band of the packing read; forced to sRGB it is
// floats.
TEST(Textures, HdrTexelsKeptAsRgbeReadAsTheirFloatDecoding) {
  const std::string dir = test::make_temp_dir("texrgbe");
  const int width = 37, height = 150;
  std::vector<float> pixels(size_t(width) * height * 3);
  for (size_t i = 0; i < pixels.size(); ++i)  // 1e-12 .. 1e12, zeros, and channels far apart in one texel
    pixels[i] = i % 11 == 0 ? 0.0f : std::pow(10.0f, float(int(i * 7919 % 25) - 12)) * (1.0f + float(i % 13) / 7);
  const std::string path = dir + "/sky.hdr";
  const auto write_hdr = [&](const std::string& file) {
    return write_image(file, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), OIIO::TypeDesc::FLOAT,
                       pixels.data());
  };
  ASSERT_TRUE(write_hdr(path));
  const ImageDesc floats = read_image_file(path, ColorSpace::Linear);
  const ImageDesc rgbe = read_image_file(path, ColorSpace::Linear, TexelStorage::Compact);
  ASSERT_FALSE(floats.holds_rgbe());
  ASSERT_TRUE(rgbe.holds_rgbe());
  EXPECT_EQ(rgbe.memory_bytes() * 3, floats.memory_bytes());
  EXPECT_TRUE(same_texels(rgbe, floats));
  const std::vector<unsigned char> hdr = file_bytes(path);
  const ImageDesc decoded = decode_image(hdr.data(), hdr.size(), ColorSpace::Auto, path, "image", TexelStorage::Compact);
  EXPECT_TRUE(decoded.holds_rgbe());
  EXPECT_TRUE(same_texels(decoded, floats));
  const ImageDesc srgb = decode_image(hdr.data(), hdr.size(), ColorSpace::Srgb, path, "image", TexelStorage::Compact);
  EXPECT_FALSE(srgb.holds_rgbe());
  // OpenImageIO 2.4 decodes a few exponents (2^87 among them) a little off the power of two: a file
  // with one such texel in its last band is read again, as floats.
  pixels[pixels.size() - 2] = 166 * 0x1p87f;
  const std::string odd = dir + "/odd.hdr";
  ASSERT_TRUE(write_hdr(odd));
  const ImageDesc odd_floats = read_image_file(odd, ColorSpace::Linear);
  const ImageDesc odd_compact = read_image_file(odd, ColorSpace::Linear, TexelStorage::Compact);
  EXPECT_EQ(odd_compact.holds_rgbe(), !!exact_rgbe(odd_floats.texel(width - 1, height - 1).rgb));
  EXPECT_TRUE(same_texels(odd_compact, odd_floats));
  const std::vector<unsigned char> odd_hdr = file_bytes(odd);
  EXPECT_TRUE(same_texels(decode_image(odd_hdr.data(), odd_hdr.size(), ColorSpace::Auto, odd, "image"), odd_floats));
}

}  // namespace
}  // namespace prism
