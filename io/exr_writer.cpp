#include "io/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>
#include <Imath/half.h>

#include <cmath>
#include <exception>
#include <limits>
#include <map>

#include "io/atomic_file.h"
#include "io/errors.h"

namespace prism {
namespace {

Imf::PixelType imf_type(ExrPixelType t) {
  switch (t) {
    case ExrPixelType::Half: return Imf::HALF;
    case ExrPixelType::Uint: return Imf::UINT;
    case ExrPixelType::Float: break;
  }
  return Imf::FLOAT;
}

Imf::Compression imf_compression(ExrCompression c) {
  switch (c) {
    case ExrCompression::None: return Imf::NO_COMPRESSION;
    case ExrCompression::Piz: return Imf::PIZ_COMPRESSION;
    case ExrCompression::Dwaa: return Imf::DWAA_COMPRESSION;
    case ExrCompression::Zip: break;
  }
  return Imf::ZIP_COMPRESSION;
}

Imath::Box2i box(const PixelWindow& w) { return Imath::Box2i({w.x0, w.y0}, {w.x1 - 1, w.y1 - 1}); }

// The part a channel belongs to in a multi-part file: its layer, or "rgba" for R, G, B, A, Z.
std::string part_of(const std::string& channel) {
  const size_t dot = channel.rfind('.');
  return dot == std::string::npos ? "rgba" : channel.substr(0, dot);
}

// A channel's pixels as the file will hold them: finite, and within a half's range for half.
struct StoredChannel {
  const ExrChannel* source;
  std::vector<float> floats;
  std::vector<half> halves;
};

}  // namespace

std::vector<ExrChannel> rgba_channels(int width, int height, const std::vector<float>& rgba, ExrPixelType type) {
  std::vector<ExrChannel> out;
  const size_t n = size_t(width) * size_t(height);
  for (int c = 0; c < 4; ++c) {
    ExrChannel ch{std::string(1, "RGBA"[c]), type, std::vector<float>(n), {}};
    for (size_t i = 0; i < n && 4 * i + c < rgba.size(); ++i) ch.values[i] = rgba[4 * i + c];
    out.push_back(std::move(ch));
  }
  return out;
}

ExrWriteReport write_exr(const std::string& path, int width, int height, const std::vector<float>& rgba,
                         const std::vector<ExrAttribute>& attributes, ExrPixelType type) {
  if (rgba.size() != size_t(width) * height * 4) throw OutputError(path, "pixel buffer does not match the image size");
  ExrImage image;
  image.display = image.data = {0, 0, width, height};
  image.channels = rgba_channels(width, height, rgba, type);
  image.attributes = attributes;
  return write_exr(path, image);
}

ExrWriteReport write_exr(const std::string& path, const ExrImage& image) {
  const PixelWindow& dw = image.data;
  if (image.display.x0 != 0 || image.display.y0 != 0 || image.display.width() <= 0 || image.display.height() <= 0 ||
      dw.width() <= 0 || dw.height() <= 0 || dw.x0 < 0 || dw.y0 < 0 || dw.x1 > image.display.x1 ||
      dw.y1 > image.display.y1)
    throw OutputError(path, "the data window must be a non-empty part of the display window");
  const size_t pixels = size_t(dw.width()) * size_t(dw.height());
  ExrWriteReport report;
  std::vector<StoredChannel> stored;
  for (const ExrChannel& c : image.channels) {
    const size_t size = c.type == ExrPixelType::Uint ? c.bits.size() : c.values.size();
    if (size != pixels) throw OutputError(path, "channel " + c.name + " does not match the image size");
    StoredChannel s{&c, {}, {}};
    if (c.type != ExrPixelType::Uint) {
      // NaN becomes 0, +-Inf +-largest (counted as non-finite), finite values beyond the type's
      // range +-largest (counted as clamped).
      const float largest = c.type == ExrPixelType::Half ? kHalfMax : std::numeric_limits<float>::max();
      s.floats = c.values;
      for (float& v : s.floats) {
        if (std::abs(v) <= largest) continue;
        ++(std::isfinite(v) ? report.clamped : report.nonfinite);
        v = std::isnan(v) ? 0.0f : std::copysign(largest, v);
      }
      if (c.type == ExrPixelType::Half) {
        s.halves.assign(s.floats.begin(), s.floats.end());  // round to nearest; in range, so finite
        s.floats.clear();
      }
    }
    stored.push_back(std::move(s));
  }

  // Parts in order of their first channel; a single part holds everything.
  std::vector<std::string> part_names;
  std::map<std::string, std::vector<const StoredChannel*>> parts;
  for (const StoredChannel& s : stored) {
    const std::string part = image.multipart ? part_of(s.source->name) : "rgba";
    if (!parts.count(part)) part_names.push_back(part);
    parts[part].push_back(&s);
  }
  if (part_names.empty()) throw OutputError(path, "an image needs at least one channel");

  AtomicFile out(path);
  try {
    std::vector<Imf::Header> headers;
    std::vector<Imf::FrameBuffer> buffers;
    for (const std::string& part : part_names) {
      Imf::Header header(box(image.display), box(dw));
      header.compression() = imf_compression(image.compression);
      if (image.multipart) {
        header.setName(part);
        header.setType(Imf::SCANLINEIMAGE);
      }
      for (const auto& [key, value] : image.attributes) {
        if (const auto* s = std::get_if<std::string>(&value)) header.insert(key, Imf::StringAttribute(*s));
        else if (const auto* i = std::get_if<int>(&value)) header.insert(key, Imf::IntAttribute(*i));
        else if (const auto* d = std::get_if<double>(&value)) header.insert(key, Imf::DoubleAttribute(*d));
        else {
          const ExrMatrix& m = std::get<ExrMatrix>(value);
          header.insert(key, Imf::M44fAttribute(Imath::M44f(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9],
                                                            m[10], m[11], m[12], m[13], m[14], m[15])));
        }
      }
      Imf::FrameBuffer fb;
      for (const StoredChannel* s : parts[part]) {
        const ExrChannel& c = *s->source;
        header.channels().insert(c.name, Imf::Channel(imf_type(c.type)));
        char* base = c.type == ExrPixelType::Uint   ? reinterpret_cast<char*>(const_cast<uint32_t*>(c.bits.data()))
                     : c.type == ExrPixelType::Half ? reinterpret_cast<char*>(const_cast<half*>(s->halves.data()))
                                                    : reinterpret_cast<char*>(const_cast<float*>(s->floats.data()));
        const size_t xs = c.type == ExrPixelType::Half ? sizeof(half) : 4;
        fb.insert(c.name, Imf::Slice::Make(imf_type(c.type), base, box(dw), xs, xs * size_t(dw.width())));
      }
      headers.push_back(header);
      buffers.push_back(fb);
    }
    if (!image.multipart) {
      Imf::OutputFile file(out.temp_path().c_str(), headers[0]);
      file.setFrameBuffer(buffers[0]);
      file.writePixels(dw.height());
    } else {
      Imf::MultiPartOutputFile file(out.temp_path().c_str(), headers.data(), int(headers.size()));
      for (size_t p = 0; p < headers.size(); ++p) {
        Imf::OutputPart part(file, int(p));
        part.setFrameBuffer(buffers[p]);
        part.writePixels(dw.height());
      }
    }
  } catch (const std::exception& e) {
    throw OutputError(path, std::string("cannot write EXR: ") + e.what());
  }
  out.commit();
  return report;
}

}  // namespace prism
