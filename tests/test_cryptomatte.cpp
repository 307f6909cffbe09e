// Cryptomatte: MurmurHash3 reference vectors, the float id conversion, rank layers, metadata, read-back.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "io/cryptomatte.h"

namespace prism {
namespace {

// Published MurmurHash3_x86_32 vectors, each also checked against an independent implementation.
TEST(Cryptomatte, MurmurHash3MatchesReferenceVectors) {
  EXPECT_EQ(murmur_hash3_32(""), 0x00000000u);
  EXPECT_EQ(murmur_hash3_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmur_hash3_32("", 0xffffffffu), 0x81f16f39u);
  EXPECT_EQ(murmur_hash3_32("test"), 0xba6bd213u);
  EXPECT_EQ(murmur_hash3_32("Hello, world!", 1234), 0xfaf6cdb3u);
  EXPECT_EQ(murmur_hash3_32("The quick brown fox jumps over the lazy dog", 0x9747b28cu), 0x2fa826cdu);
  EXPECT_EQ(murmur_hash3_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
  // Every tail length: 1, 2, 3 bytes, a whole block, a block and one byte.
  EXPECT_EQ(murmur_hash3_32("a"), 0x3c2569b2u);
  EXPECT_EQ(murmur_hash3_32("ab"), 0x9bbfd75fu);
  EXPECT_EQ(murmur_hash3_32("abc"), 0xb3dd93fau);
  EXPECT_EQ(murmur_hash3_32("aaaa"), 0x7eeed987u);
  EXPECT_EQ(murmur_hash3_32("aaaaa"), 0xe9ca302bu);
  EXPECT_EQ(murmur_hash3_32("hello"), 0x248bfa47u);
  // Bytes >= 0x80 must not sign-extend when read from a (signed) char; NUL is a byte like any other.
  EXPECT_EQ(murmur_hash3_32("\xff\xfe\xfd"), 0xd2bef2dcu);
  EXPECT_EQ(murmur_hash3_32("\x80"), 0x0feb9e1du);
  EXPECT_EQ(murmur_hash3_32(std::string_view("a\0b", 3)), 0x6f8cc6a6u);
}

// The spec's own manifest example (section 1.e): "bunny", "default", "bunny_porcelain_mat".
TEST(Cryptomatte, IdsMatchTheSpecificationExample) {
  EXPECT_EQ(cryptomatte_id_bits("bunny"), 0x13851a76u);
  EXPECT_EQ(cryptomatte_id_bits("default"), 0x42c9679fu);
  EXPECT_EQ(cryptomatte_id_bits("bunny_porcelain_mat"), 0xb24b26d4u);
}

// Float ids from Psyop's own test suite (nuke/cryptomatte_utilities_tests.py), including UTF-8 names,
// and ids Blender wrote for Kubric's test suite.
TEST(Cryptomatte, FloatIdsMatchOtherImplementations) {
  EXPECT_EQ(cryptomatte_id("hello"), static_cast<float>(6.0705627102400005616e-17));
  EXPECT_EQ(cryptomatte_id("cube"), static_cast<float>(-4.08461912519e+15));
  EXPECT_EQ(cryptomatte_id("sphere"), static_cast<float>(2.79018604383e+15));
  EXPECT_EQ(cryptomatte_id("plane"), static_cast<float>(3.66557617593e-11));
  EXPECT_EQ(cryptomatte_id("\xd1\x80\xd0\xb0\xd0\xb2\xd0\xbd\xd0\xb8\xd0\xbd\xd0\xb0"),  // "равнина"
            static_cast<float>(-1.3192631212399999468e-25));
  EXPECT_EQ(cryptomatte_id("m\xc3\xa4""dchen"), static_cast<float>(6.2361298211599995797e+25));  // "mädchen"
  EXPECT_EQ(cryptomatte_id_bits("Static"), 3498399415u);
  EXPECT_EQ(cryptomatte_id_bits("Object_41"), 12644183u);  // exponent 1: the smallest kept as is
  EXPECT_EQ(cryptomatte_id_bits("Object_12"), 4248664771u);
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_id("bunny")), cryptomatte_id_bits("bunny"));
}

TEST(Cryptomatte, ExponentsZeroAnd255AreMovedInsideTheNormalRange) {
  // Names whose raw hash has exponent 0 (a negative denormal) and 255 (a NaN): bit 23 flips.
  EXPECT_EQ(murmur_hash3_32("object_491"), 0x80638c9fu);
  EXPECT_EQ(cryptomatte_id_bits("object_491"), 0x80e38c9fu);
  EXPECT_EQ(murmur_hash3_32("object_440"), 0xffc16c53u);
  EXPECT_EQ(cryptomatte_id_bits("object_440"), 0xff416c53u);

  int low = 0, high = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::string name = "name_" + std::to_string(i);
    const uint32_t raw = murmur_hash3_32(name);
    const uint32_t bits = cryptomatte_id_bits(name);
    const uint32_t exponent = raw >> 23 & 0xffu;
    const float id = cryptomatte_id(name);
    ASSERT_TRUE(std::isfinite(id) && std::isnormal(id)) << name;
    if (exponent == 0 || exponent == 255) {
      low += exponent == 0;
      high += exponent == 255;
      ASSERT_EQ(bits, raw ^ 1u << 23) << name;
      ASSERT_EQ(bits >> 23 & 0xffu, exponent == 0 ? 1u : 254u) << name;
    } else {
      ASSERT_EQ(bits, raw) << name;
    }
  }
  EXPECT_GT(low, 0);  // both cases were met (about 1 in 256 names each)
  EXPECT_GT(high, 0);
}

TEST(Cryptomatte, LayerKeyIsTheFirstSevenHexDigitsOfTheLayerId) {
  EXPECT_EQ(cryptomatte_layer_key("CryptoObject"), "3ae39a5");    // id 3ae39a58
  EXPECT_EQ(cryptomatte_layer_key("CryptoMaterial"), "be359d6");  // id be359d67
  EXPECT_EQ(cryptomatte_layer_key("bunny"), "13851a7");
  EXPECT_EQ(cryptomatte_layer_key(""), "0080000");  // hash 0 has exponent 0, so bit 23 is set
}

TEST(Cryptomatte, AddIdSampleCountsEachIdOnce) {
  PixelIdCounts pixel;
  add_id_sample(pixel, 7);
  add_id_sample(pixel, 3);
  add_id_sample(pixel, 7);
  add_id_sample(pixel, 7);
  ASSERT_EQ(pixel.size(), 2u);
  const auto count_of = [&](uint32_t id) {
    for (const IdCount& e : pixel)
      if (e.id == id) return e.count;
    return 0u;
  };
  EXPECT_EQ(count_of(7), 3u);
  EXPECT_EQ(count_of(3), 1u);
}

uint32_t bits_of(float f) { return std::bit_cast<uint32_t>(f); }

TEST(Cryptomatte, ChannelsRankIdsByCoverageOnATwoPixelImage) {
  const uint32_t a = cryptomatte_id_bits("a"), b = cryptomatte_id_bits("b");
  const uint32_t c = cryptomatte_id_bits("c"), d = cryptomatte_id_bits("d");
  const uint32_t lo = std::min(c, d), hi = std::max(c, d);
  // Pixel 0: a 3, b 5, c 1, d 1 of 10 samples (c and d tie: the lower id ranks first). Pixel 1 has
  // ids but no samples, so it stays empty.
  std::vector<PixelIdCounts> pixels(2);
  for (int i = 0; i < 3; ++i) add_id_sample(pixels[0], a);
  add_id_sample(pixels[0], hi);
  for (int i = 0; i < 5; ++i) add_id_sample(pixels[0], b);
  add_id_sample(pixels[0], lo);
  add_id_sample(pixels[1], a);

  const std::vector<ExrChannel> ch = cryptomatte_channels("CryptoObject", pixels, {10, 0}, 3);
  ASSERT_EQ(ch.size(), 8u);  // ceil(3 / 2) = 2 rank layers
  const char* names[] = {"CryptoObject00.R", "CryptoObject00.G", "CryptoObject00.B", "CryptoObject00.A",
                         "CryptoObject01.R", "CryptoObject01.G", "CryptoObject01.B", "CryptoObject01.A"};
  for (size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(ch[i].name, names[i]);
    EXPECT_EQ(ch[i].type, ExrPixelType::Float);
    ASSERT_EQ(ch[i].values.size(), 2u);
    EXPECT_EQ(ch[i].values[1], 0.0f) << names[i];  // no samples: all zero
    EXPECT_TRUE(ch[i].bits.empty());
  }
  EXPECT_EQ(bits_of(ch[0].values[0]), b);  // rank 0
  EXPECT_FLOAT_EQ(ch[1].values[0], 0.5f);
  EXPECT_EQ(bits_of(ch[2].values[0]), a);  // rank 1
  EXPECT_FLOAT_EQ(ch[3].values[0], 0.3f);
  EXPECT_EQ(bits_of(ch[4].values[0]), lo);  // rank 2: the tie goes to the lower id
  EXPECT_FLOAT_EQ(ch[5].values[0], 0.1f);
  EXPECT_EQ(ch[6].values[0], 0.0f);  // rank 3 is beyond ranks = 3: unused even though hi exists
  EXPECT_EQ(ch[7].values[0], 0.0f);
}

TEST(Cryptomatte, DefaultSixRanksWriteThreeLayersAndLeaveUnusedRanksZero) {
  std::vector<PixelIdCounts> pixels(1);
  add_id_sample(pixels[0], cryptomatte_id_bits("only"));
  add_id_sample(pixels[0], cryptomatte_id_bits("only"));
  const std::vector<ExrChannel> ch = cryptomatte_channels("L", pixels, {4});
  ASSERT_EQ(ch.size(), 12u);
  EXPECT_EQ(ch[11].name, "L02.A");
  EXPECT_EQ(bits_of(ch[0].values[0]), cryptomatte_id_bits("only"));
  EXPECT_EQ(ch[1].values[0], 0.5f);
  for (size_t i = 2; i < 12; ++i) EXPECT_EQ(ch[i].values[0], 0.0f) << ch[i].name;
}

TEST(Cryptomatte, ChannelsRejectMismatchedInputs) {
  EXPECT_THROW(cryptomatte_channels("L", std::vector<PixelIdCounts>(2), {1}), std::invalid_argument);
  EXPECT_THROW(cryptomatte_channels("L", std::vector<PixelIdCounts>(1), {1}, 0), std::invalid_argument);
}

ExrImage image_of(std::vector<ExrChannel> channels, int width, int height) {
  ExrImage image;
  image.display = {0, 0, width + 2, height + 1};
  image.data = {1, 1, 1 + width, 1 + height};  // a crop: counts follow the data window
  image.channels = std::move(channels);
  return image;
}

// (id, count) pairs in id order, to compare pixels whatever order their ids were met in.
std::vector<std::pair<uint32_t, uint32_t>> sorted(const PixelIdCounts& p) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const IdCount& e : p) out.emplace_back(e.id, e.count);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Cryptomatte, CountsRoundTripThroughTheChannels) {
  const int width = 4, height = 2;
  const std::vector<uint64_t> samples = {16, 1, 0, 1000003, 7, 65536, 6, 50000017};
  std::vector<PixelIdCounts> pixels(samples.size());
  const auto fill = [&](size_t p, std::initializer_list<std::pair<const char*, uint32_t>> ids) {
    for (const auto& [name, count] : ids)
      for (uint32_t i = 0; i < count; ++i) add_id_sample(pixels[p], cryptomatte_id_bits(name));
  };
  fill(0, {{"a", 5}, {"b", 4}, {"c", 3}, {"d", 2}, {"e", 1}, {"object_491", 1}});  // six ranks, edge-case id
  fill(1, {{"a", 1}});
  // Coverages near 1 and 1e-6 still round trip.
  pixels[3] = {{cryptomatte_id_bits("x"), 1000000}, {cryptomatte_id_bits("y"), 2}, {cryptomatte_id_bits("z"), 1}};
  fill(4, {{"object_440", 4}, {"b", 3}});
  fill(5, {{"a", 40000}, {"b", 25535}, {"c", 1}});
  fill(6, {{"a", 5}, {"b", 1}});  // float(5 / 6) * 6 is just below 5: counts must round, not truncate
  // Float coverage keeps counts below 2^23 exact, but only if coverage * samples is taken in double:
  // in float, 8029919 of 50000017 would come back 8029918.
  pixels[7] = {{cryptomatte_id_bits("a"), 8029919}, {cryptomatte_id_bits("b"), 17}, {cryptomatte_id_bits("c"), 3}};

  const ExrImage image = image_of(cryptomatte_channels("CryptoAsset", pixels, samples), width, height);
  const std::vector<PixelIdCounts> back = cryptomatte_counts(image, "CryptoAsset", samples);
  ASSERT_EQ(back.size(), pixels.size());
  for (size_t p = 0; p < pixels.size(); ++p) EXPECT_EQ(sorted(back[p]), sorted(pixels[p])) << "pixel " << p;

  // Merging two partial renders: counts read back from each add up to those of one render.
  std::vector<PixelIdCounts> merged = back;
  for (size_t p = 0; p < merged.size(); ++p)
    for (const IdCount& e : back[p])
      for (uint32_t i = 0; i < e.count; ++i) add_id_sample(merged[p], e.id);
  for (const IdCount& e : merged[0]) EXPECT_EQ(e.count % 2, 0u);
  EXPECT_EQ(merged[3].size(), 3u);
}

TEST(Cryptomatte, CountsKeepOnlyTheStoredRanks) {
  std::vector<PixelIdCounts> pixels(1);
  for (const char* name : {"a", "b", "c"})
    for (int i = 0; i < (name[0] == 'a' ? 3 : name[0] == 'b' ? 2 : 1); ++i)
      add_id_sample(pixels[0], cryptomatte_id_bits(name));
  const ExrImage image = image_of(cryptomatte_channels("L", pixels, {6}, 2), 1, 1);
  ASSERT_EQ(image.channels.size(), 4u);
  const std::vector<PixelIdCounts> back = cryptomatte_counts(image, "L", {6});
  EXPECT_EQ(sorted(back[0]), sorted(PixelIdCounts{{cryptomatte_id_bits("a"), 3}, {cryptomatte_id_bits("b"), 2}}));
  EXPECT_TRUE(cryptomatte_counts(image, "Other", {6})[0].empty());  // no such layer: nothing
}

TEST(Cryptomatte, CountsRejectIncompleteLayersAndWrongSizes) {
  std::vector<PixelIdCounts> pixels(2);
  add_id_sample(pixels[0], cryptomatte_id_bits("a"));
  ExrImage image = image_of(cryptomatte_channels("L", pixels, {1, 1}), 2, 1);
  EXPECT_THROW(cryptomatte_counts(image, "L", {1, 1, 1}), std::invalid_argument);
  image.channels[5].values.pop_back();  // L01.G too short
  EXPECT_THROW(cryptomatte_counts(image, "L", {1, 1}), std::runtime_error);
  image.channels.erase(image.channels.begin() + 1);  // drop L00.G
  EXPECT_THROW(cryptomatte_counts(image, "L", {1, 1}), std::runtime_error);
}

std::string string_attribute(const std::vector<ExrAttribute>& attributes, const std::string& name) {
  for (const auto& [key, value] : attributes)
    if (key == name) return std::get<std::string>(value);
  ADD_FAILURE() << "no attribute " << name;
  return {};
}

TEST(Cryptomatte, AttributesHoldMetadataAndAnEscapedManifest) {
  const std::string tricky = "a\"b\\c";  // a"b\c
  const std::vector<ExrAttribute> attributes =
      cryptomatte_attributes("CryptoObject", {"bunny", tricky, "default", tricky, "b"});
  ASSERT_EQ(attributes.size(), 4u);
  EXPECT_EQ(string_attribute(attributes, "cryptomatte/3ae39a5/name"), "CryptoObject");
  EXPECT_EQ(string_attribute(attributes, "cryptomatte/3ae39a5/hash"), "MurmurHash3_32");
  EXPECT_EQ(string_attribute(attributes, "cryptomatte/3ae39a5/conversion"), "uint32_to_float32");

  const std::string manifest = string_attribute(attributes, "cryptomatte/3ae39a5/manifest");
  // Sorted by name, each once; ids of a"b\c and b from an independent MurmurHash3 implementation.
  EXPECT_EQ(manifest, R"({"a\"b\\c":"e2f273f2","b":"95de7e03","bunny":"13851a76","default":"42c9679f"})");
  const nlohmann::json parsed = nlohmann::json::parse(manifest);
  ASSERT_EQ(parsed.size(), 4u);
  EXPECT_EQ(parsed.at(tricky), "e2f273f2");
  EXPECT_EQ(std::stoul(parsed.at(tricky).get<std::string>(), nullptr, 16), cryptomatte_id_bits(tricky));
}

TEST(Cryptomatte, ManifestOfNoNamesIsAnEmptyObject) {
  const std::vector<ExrAttribute> attributes = cryptomatte_attributes("L", {});
  EXPECT_EQ(string_attribute(attributes, "cryptomatte/" + cryptomatte_layer_key("L") + "/manifest"), "{}");
}

}  // namespace
}  // namespace prism
