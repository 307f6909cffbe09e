// The memory limit: sizes parse and print as a user writes them, estimates past the limit are
// refused with both sizes before anything is allocated, and the loader sums a scene's parts. Also
// huge pages for large buffers, a hint that must change no value.
#include <gtest/gtest.h>

#include "core/environment_light.h"
#include "core/film.h"
#include "core/huge_pages.h"
#include "core/memory_limit.h"
#include "core/mip_levels.h"
#include "io/gltf_loader.h"

namespace prism {
namespace {

// Sets the limit for one test and restores the previous one.
class ScopedMemoryLimit {
 public:
  explicit ScopedMemoryLimit(uint64_t bytes) : previous_(memory_limit()) { set_memory_limit(bytes); }
  ~ScopedMemoryLimit() { set_memory_limit(previous_); }

 private:
  uint64_t previous_;
};

TEST(MemoryLimit, SizesParseAndPrint) {
  EXPECT_EQ(parse_byte_size("8G"), uint64_t(8) << 30);
  EXPECT_EQ(parse_byte_size("512M"), uint64_t(512) << 20);
  EXPECT_EQ(parse_byte_size("64k"), uint64_t(64) << 10);
  EXPECT_EQ(parse_byte_size("1.5GiB"), uint64_t(3) << 29);
  EXPECT_EQ(parse_byte_size("1000"), uint64_t(1000));
  for (const char* bad : {"", "0", "-1G", "lots", "8Q", "8G more", "nan"}) EXPECT_FALSE(parse_byte_size(bad)) << bad;
  EXPECT_EQ(format_bytes(100), "100 bytes");
  EXPECT_EQ(format_bytes(uint64_t(3) << 29), "1.5 GiB");
  EXPECT_EQ(format_bytes(uint64_t(640) << 20), "640 MiB");
}

TEST(MemoryLimit, TheDefaultIsTheMemoryTheSystemHas) {
  EXPECT_GT(default_memory_limit(), uint64_t(64) << 20);
}

TEST(MemoryLimit, AFilmPastTheLimitIsRefusedWithItsEstimate) {
  const ScopedMemoryLimit limit(uint64_t(64) << 20);
  EXPECT_NO_THROW(Film(256, 256));
  try {
    Film film(8192, 8192);
    FAIL() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_STREQ(e.what(), "a 8192x8192 film needs about 6.0 GiB, more than the memory limit of 64 MiB (--memory-limit)");
  }
}

// An environment map's sampling distribution takes more than its texels (a double per texel for
// the CDFs): the two together are estimated, and refused before the distribution is built.
TEST(MemoryLimit, AnEnvironmentMapsDistributionPastTheLimitIsRefused) {
  const ScopedMemoryLimit limit(uint64_t(16) << 20);
  const auto sky = [](int width, int height) {
    SceneDesc desc;
    desc.environment.present = true;
    desc.environment.image = 0;
    ImageDesc& img = desc.images.emplace_back();
    img.name = "sky.exr";
    img.width = width;
    img.height = height;
    img.channels = 1;
    img.texels.assign(size_t(width) * height, 1.0f);
    return desc;
  };
  const SceneDesc small = sky(512, 256), large = sky(2048, 1024);  // 8 MiB of texels, 10 MiB more to sample them
  EXPECT_NO_THROW(EnvironmentLight{small});
  try {
    const EnvironmentLight env(large);
    FAIL() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "sky.exr: the environment map with its sampling distribution needs about 18 MiB, more than the memory "
                 "limit of 16 MiB (--memory-limit)");
  }
}

// MIP levels add a third of each filtered texture's texels (as codes for 8-bit images), checked
// with the images already held, before any level is built.
TEST(MemoryLimit, MipLevelsPastTheLimitAreRefused) {
  const ScopedMemoryLimit limit(uint64_t(16) << 20);
  SceneDesc desc;
  ImageDesc& img = desc.images.emplace_back();
  img.width = img.height = 2048;
  img.channels = 3;
  img.bytes.assign(size_t(2048) * 2048 * 3, 128);  // 12 MiB: with its levels, 16 MiB and a bit
  desc.textures.push_back(TextureDesc{});
  desc.textures[0].image = 0;
  desc.materials.emplace_back().base_color_texture.texture = 0;
  try {
    build_texture_mips(desc, "yard.glb");
    FAIL() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_STREQ(e.what(),
                 "yard.glb: the textures with their MIP levels needs about 16 MiB, more than the memory limit of 16 "
                 "MiB (--memory-limit)");
  }
  EXPECT_TRUE(desc.images[0].mips.empty());
  const ScopedMemoryLimit roomy(uint64_t(17) << 20);
  build_texture_mips(desc, "yard.glb");
  EXPECT_EQ(desc.images[0].mips.size(), 11u);  // 1024^2 ... 1^2
}

// Huge pages are a hint to the kernel: a buffer resized on them holds what it held, zeros after it,
// and ranges too small or unaligned for a huge page are left alone.
TEST(HugePages, AResizedBufferKeepsItsValues) {
  std::vector<float> v = {1, 2, 3};
  resize_on_huge_pages(v, size_t(3) << 20);  // 12 MiB
  ASSERT_EQ(v.size(), size_t(3) << 20);
  EXPECT_EQ(v[0], 1.0f);
  EXPECT_EQ(v[2], 3.0f);
  EXPECT_EQ(v[3], 0.0f);
  EXPECT_EQ(v.back(), 0.0f);
  resize_on_huge_pages(v, 2);
  EXPECT_EQ(v, (std::vector<float>{1, 2}));
  float small[3] = {4, 5, 6};
  advise_huge_pages(small + 1, sizeof(float));
  EXPECT_EQ(small[1], 5.0f);
}

TEST(MemoryLimit, TheTallyAddsAScenesParts) {
  const ScopedMemoryLimit limit(1000);
  MemoryTally tally;
  tally.add(600, "mesh 0");
  try {
    tally.add(600, "mesh 1");
    FAIL() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_STREQ(e.what(), "mesh 1 brings the estimate to about 1.2 KiB, more than the memory limit of 1000 bytes (--memory-limit)");
  }
}

// A declared 2^28 zero vertices (an accessor without a bufferView) is refused before its 9 GiB
// are allocated; under a roomy limit the same loader reads the valid triangle.
TEST(MemoryLimit, TheLoaderRefusesAnAccessorPastTheLimit) {
  const ScopedMemoryLimit limit(uint64_t(1) << 30);
  Diagnostics diag;
  EXPECT_NO_THROW(load_gltf(PRISM_SOURCE_DIR "/tests/broken/triangle.gltf", diag));
  try {
    load_gltf(PRISM_SOURCE_DIR "/tests/broken/absurd-count-no-view.gltf", diag);
    FAIL() << "expected a MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("POSITION (accessor 0) needs about 9.0 GiB, more than the memory limit of 1.0 GiB"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace prism
