#include "io/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <cmath>
#include <exception>
#include <limits>

#include "io/atomic_file.h"
#include "io/errors.h"

namespace prism {

int write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
              const std::vector<ExrAttribute>& attributes, const std::vector<ExrChannel>& extra) {
  if (rgba.size() != size_t(width) * height * 4) throw OutputError(path, "pixel buffer does not match the image size");
  for (const ExrChannel& c : extra)
    if (c.pixels.size() != size_t(width) * height)
      throw OutputError(path, "channel " + c.name + " does not match the image size");
  int replaced = 0;
  auto finite = [&](std::vector<float> values) {
    for (float& v : values) {
      if (std::isfinite(v)) continue;
      v = std::isnan(v) ? 0.0f : std::copysign(std::numeric_limits<float>::max(), v);
      ++replaced;
    }
    return values;
  };
  std::vector<float> pixels = finite(rgba);
  std::vector<std::vector<float>> extra_pixels;
  for (const ExrChannel& c : extra) extra_pixels.push_back(finite(c.pixels));

  AtomicFile out(path);
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* name : {"R", "G", "B", "A"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const ExrChannel& c : extra) header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    for (const auto& [key, value] : attributes) {
      if (const auto* s = std::get_if<std::string>(&value)) header.insert(key, Imf::StringAttribute(*s));
      else if (const auto* i = std::get_if<int>(&value)) header.insert(key, Imf::IntAttribute(*i));
      else header.insert(key, Imf::DoubleAttribute(std::get<double>(value)));
    }
    Imf::FrameBuffer fb;
    const size_t xs = 4 * sizeof(float), ys = xs * size_t(width);
    const char* names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c)
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), xs, ys));
    for (size_t c = 0; c < extra.size(); ++c)
      fb.insert(extra[c].name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(extra_pixels[c].data()), sizeof(float),
                                          sizeof(float) * size_t(width)));
    Imf::OutputFile file(out.temp_path().c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
  } catch (const std::exception& e) {
    throw OutputError(path, std::string("cannot write EXR: ") + e.what());
  }
  out.commit();
  return replaced;
}

}  // namespace prism
