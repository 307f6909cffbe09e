// The EXR image model: channels of every pixel type, data windows inside display windows, parts,
// compressions and reproducible bytes; the camera matrices compositors re-project with.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/camera.h"
#include "gltf_writer.h"
#include "io/camera_attributes.h"
#include "io/errors.h"
#include "io/exr_reader.h"
#include "io/exr_writer.h"

namespace prism {
namespace {

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A 7x5 crop at (3, 2) of a 16x10 image: half beauty, float data, a uint channel, attributes.
ExrImage sample_image() {
  ExrImage image;
  image.display = {0, 0, 16, 10};
  image.data = {3, 2, 10, 7};
  const size_t n = 7 * 5;
  auto ramp = [&](float scale) {
    std::vector<float> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = scale * float(i) + 0.25f;
    return v;
  };
  for (const char* c : {"R", "G", "B", "A"}) image.channels.push_back({c, ExrPixelType::Half, ramp(0.5f), {}});
  image.channels.push_back({"N.X", ExrPixelType::Float, ramp(1e-3f), {}});
  image.channels.push_back({"Z", ExrPixelType::Float, ramp(1e7f), {}});
  std::vector<uint32_t> bits(n);
  for (size_t i = 0; i < n; ++i) bits[i] = 0xdeadbeefu ^ uint32_t(i * 2654435761u);
  image.channels.push_back({"state.count", ExrPixelType::Uint, {}, bits});
  image.attributes = {{"prism/spp", 64}, {"prism/seed", std::string("7")}, {"prism/relativeError", 0.125}};
  ExrMatrix m;
  for (int i = 0; i < 16; ++i) m[size_t(i)] = float(i) - 3.5f;
  image.attributes.push_back({"worldToCamera", m});
  return image;
}

void expect_same_pixels(const ExrImage& read, const ExrImage& written) {
  EXPECT_EQ(read.display, written.display);
  EXPECT_EQ(read.data, written.data);
  for (const ExrChannel& w : written.channels) {
    const ExrChannel* r = read.find(w.name);
    ASSERT_NE(r, nullptr) << w.name;
    EXPECT_EQ(r->type, w.type) << w.name;
    if (w.type == ExrPixelType::Uint) EXPECT_EQ(r->bits, w.bits) << w.name;
    else EXPECT_EQ(r->values, w.values) << w.name;  // the ramps are exact in half
  }
}

TEST(ExrLayers, EveryCompressionAndLayoutRoundTripsChannelByChannel) {
  const std::string dir = test::make_temp_dir("layers");
  for (const char* compression : {"zip", "piz", "none", "dwaa"})
    for (bool multipart : {false, true}) {
      ExrImage image = sample_image();
      image.compression = *parse_exr_compression(compression);
      image.multipart = multipart;
      const std::string path = dir + "/" + compression + (multipart ? "-multi" : "-single") + ".exr";
      write_exr(path, image);
      const ExrImage read = read_exr(path);
      SCOPED_TRACE(path);
      EXPECT_EQ(read.multipart, multipart);
      EXPECT_EQ(read.compression, image.compression);
      if (std::string(compression) != "dwaa") expect_same_pixels(read, image);
      else EXPECT_EQ(read.find("state.count")->bits, image.find("state.count")->bits) << "uint data is never lossy";
      ASSERT_NE(read.attribute("worldToCamera"), nullptr);
      EXPECT_EQ(std::get<ExrMatrix>(read.attribute("worldToCamera")->second), std::get<ExrMatrix>(image.attributes[3].second));
      EXPECT_EQ(std::get<int>(read.attribute("prism/spp")->second), 64);
      EXPECT_EQ(std::get<double>(read.attribute("prism/relativeError")->second), 0.125);
    }
}

TEST(ExrLayers, OpenImageIOSeesTheCropInsideTheDisplayWindow) {
  const std::string path = test::make_temp_dir("layers") + "/crop.exr";
  write_exr(path, sample_image());
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  EXPECT_EQ(spec.x, 3);
  EXPECT_EQ(spec.y, 2);
  EXPECT_EQ(spec.width, 7);
  EXPECT_EQ(spec.height, 5);
  EXPECT_EQ(spec.full_width, 16);
  EXPECT_EQ(spec.full_height, 10);
  EXPECT_EQ(spec.nchannels, 7);
  EXPECT_EQ(spec.channelformat(spec.channelindex("R")), OIIO::TypeDesc::HALF);
  EXPECT_EQ(spec.channelformat(spec.channelindex("Z")), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(spec.channelformat(spec.channelindex("state.count")), OIIO::TypeDesc::UINT);
}

TEST(ExrLayers, TheSameImageGivesTheSameBytes) {
  const std::string dir = test::make_temp_dir("layers");
  for (bool multipart : {false, true}) {
    ExrImage image = sample_image();
    image.multipart = multipart;
    write_exr(dir + "/a.exr", image);
    write_exr(dir + "/b.exr", image);
    EXPECT_EQ(bytes_of(dir + "/a.exr"), bytes_of(dir + "/b.exr"));
  }
}

TEST(ExrLayers, UnreadableFilesAreInputErrorsNamingTheFile) {
  const std::string dir = test::make_temp_dir("layers");
  std::ofstream(dir + "/junk.exr") << "not an EXR at all";
  try {
    read_exr(dir + "/junk.exr");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.exr"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_exr(dir + "/missing.exr"), InputError);
}

// OpenEXR allocates what a header claims before it finds the file short: the fuzzer found an
// 805-byte file whose string attribute claims 1.05 GiB (14 s and 1.4 GB to refuse). The
// header pre-scan refuses such claims first, from a file and from memory alike.
TEST(ExrLayers, HeaderClaimsPastTheEndOfTheFileAreRefusedBeforeAllocating) {
  const std::string path = PRISM_SOURCE_DIR "/tests/fuzz/regressions/exr/huge-string-attribute.exr";
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (bool from_memory : {false, true}) {
    try {
      from_memory ? read_exr_from_memory(bytes, path) : read_exr(path);
      FAIL() << "no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("huge-string-attribute.exr: part 0 attribute 'prism/projection': declares 1124073483 bytes"), std::string::npos)
          << e.what();
    }
  }
  // A 64x2^29 data window in a file of a few hundred bytes, and a tiled single-part file.
  const std::string dir = test::make_temp_dir("layers");
  ExrImage tiny;
  tiny.display = tiny.data = {0, 0, 4, 4};
  tiny.channels.push_back({"R", ExrPixelType::Float, std::vector<float>(16, 0.5f), {}});
  write_exr(dir + "/tiny.exr", tiny);
  std::ifstream tiny_in(dir + "/tiny.exr", std::ios::binary);
  std::vector<unsigned char> tall((std::istreambuf_iterator<char>(tiny_in)), std::istreambuf_iterator<char>());
  const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
  const auto at = std::search(tall.begin(), tall.end(), key.begin(), key.end()) - tall.begin();
  ASSERT_LT(size_t(at), tall.size());
  const int32_t y1 = (1 << 29) - 1;
  std::memcpy(&tall[size_t(at) + key.size() + 4 + 12], &y1, 4);
  EXPECT_THROW(
      {
        try {
          read_exr_from_memory(tall, "tall.exr");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("lines need a larger offset table than the whole file"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  std::vector<unsigned char> tiled = bytes;
  tiled[5] |= 0x02;  // the tiled flag (0x200) of the version field
  EXPECT_THROW(read_exr_from_memory(tiled, "tiled.exr"), InputError);
}

// Row vector p (x, y, z, 1) times m, divided by w.
Vec3 project(const ExrMatrix& m, const Vec3& p) {
  float out[4];
  for (int c = 0; c < 4; ++c) out[c] = p.x * m[size_t(c)] + p.y * m[size_t(4 + c)] + p.z * m[size_t(8 + c)] + m[size_t(12 + c)];
  return Vec3(out[0], out[1], out[2]) / out[3];
}

// For film positions across the image, a point along the camera's ray lands in NDC at
// (fx / width, fy / height), and in camera space at +z (in front), +x right, +y up.
TEST(ExrLayers, CameraMatricesFollowOpenExrConventions) {
  for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
    CameraDesc desc;
    desc.projection = projection;
    desc.yfov = 0.7f;
    desc.ymag = 2.5f;
    desc.camera_to_world = Transform::look_at(Vec3(3, -2, 7), Vec3(-1, 0.5f, 0), Vec3(0, 1, 0));
    const int width = 40, height = 25;
    const Camera camera(desc, width, height);
    const ExrMatrix to_camera = world_to_camera_matrix(camera), to_ndc = world_to_ndc_matrix(camera);
    for (float fx : {0.0f, 13.5f, 40.0f})
      for (float fy : {0.0f, 9.25f, 25.0f}) {
        const Ray ray = camera.generate_ray(fx, fy);
        const Vec3 p = ray.origin + ray.dir * 6.0f;
        const Vec3 ndc = project(to_ndc, p);
        EXPECT_NEAR(ndc.x, fx / width, 2e-6f) << fx << "," << fy;
        EXPECT_NEAR(ndc.y, fy / height, 2e-6f) << fx << "," << fy;
        const Vec3 c = project(to_camera, p);
        EXPECT_NEAR(c.z, camera.planar_depth(p), 1e-5f) << "+z looks forward";
        EXPECT_GT(c.z, 0.0f);
        EXPECT_EQ(c.x > 0, fx > 20.0f) << "+x is right";
        EXPECT_EQ(c.y > 0, fy < 12.5f) << "+y is up";
      }
  }
}

}  // namespace
}  // namespace prism
