#include "io/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <Imath/half.h>

#include <cmath>
#include <exception>
#include <limits>

#include "io/atomic_file.h"
#include "io/errors.h"

namespace prism {

ExrWriteReport write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
                         const std::vector<ExrAttribute>& attributes, const std::vector<ExrChannel>& extra,
                         ExrPixelType beauty) {
  if (rgba.size() != size_t(width) * height * 4) throw OutputError(path, "pixel buffer does not match the image size");
  for (const ExrChannel& c : extra)
    if (c.pixels.size() != size_t(width) * height)
      throw OutputError(path, "channel " + c.name + " does not match the image size");
  ExrWriteReport report;
  // Values are kept within `largest`: NaN becomes 0, +-Inf +-largest (counted as non-finite),
  // finite values beyond it +-largest (counted as clamped).
  auto within = [&](std::vector<float> values, float largest) {
    for (float& v : values) {
      if (std::abs(v) <= largest) continue;
      ++(std::isfinite(v) ? report.clamped : report.nonfinite);
      v = std::isnan(v) ? 0.0f : std::copysign(largest, v);
    }
    return values;
  };
  const bool half_beauty = beauty == ExrPixelType::Half;
  std::vector<float> pixels = within(rgba, half_beauty ? kHalfMax : std::numeric_limits<float>::max());
  std::vector<std::vector<float>> extra_pixels;
  for (const ExrChannel& c : extra) extra_pixels.push_back(within(c.pixels, std::numeric_limits<float>::max()));

  AtomicFile out(path);
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* name : {"R", "G", "B", "A"})
      header.channels().insert(name, Imf::Channel(half_beauty ? Imf::HALF : Imf::FLOAT));
    for (const ExrChannel& c : extra) header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    for (const auto& [key, value] : attributes) {
      if (const auto* s = std::get_if<std::string>(&value)) header.insert(key, Imf::StringAttribute(*s));
      else if (const auto* i = std::get_if<int>(&value)) header.insert(key, Imf::IntAttribute(*i));
      else header.insert(key, Imf::DoubleAttribute(std::get<double>(value)));
    }
    Imf::FrameBuffer fb;
    const char* names[4] = {"R", "G", "B", "A"};
    std::vector<half> halves;
    if (half_beauty) {
      halves.assign(pixels.begin(), pixels.end());  // round to nearest; within range, so finite
      const size_t xs = 4 * sizeof(half), ys = xs * size_t(width);
      for (int c = 0; c < 4; ++c) fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + c), xs, ys));
    } else {
      const size_t xs = 4 * sizeof(float), ys = xs * size_t(width);
      for (int c = 0; c < 4; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), xs, ys));
    }
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
  return report;
}

}  // namespace prism
