#include "io/exr_reader.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfMultiPartInputFile.h>
#include <ImfPartType.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <limits>
#include <memory>
#include <set>
#include <string>

#include "core/memory_limit.h"
#include "io/errors.h"
#include "io/exr_header_scan.h"

namespace prism {
namespace {

// The window of an EXR box (inclusive corners), checked in 64 bits so a corner at INT_MAX or a
// width past 2^31 is an error rather than an overflow.
PixelWindow window(const Imath::Box2i& b, const std::string& path, const char* what) {
  const int64_t w = int64_t(b.max.x) - b.min.x + 1, h = int64_t(b.max.y) - b.min.y + 1;
  if (w <= 0 || h <= 0 || w > (int64_t(1) << 30) || h > (int64_t(1) << 30) || b.max.x == INT32_MAX || b.max.y == INT32_MAX)
    throw InputError(path, what, "unusable window (" + std::to_string(b.min.x) + ", " + std::to_string(b.min.y) + ") to (" +
                                     std::to_string(b.max.x) + ", " + std::to_string(b.max.y) + ")");
  return {b.min.x, b.min.y, b.max.x + 1, b.max.y + 1};
}

// An EXR file's bytes already in memory, as OpenEXR's input stream.
class MemoryStream : public Imf::IStream {
 public:
  MemoryStream(const std::vector<unsigned char>& bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || uint64_t(n) > bytes_.size() - std::min<uint64_t>(at_, bytes_.size()))
      throw std::runtime_error("unexpected end of file");
    std::memcpy(c, bytes_.data() + at_, size_t(n));
    at_ += uint64_t(n);
    return at_ < bytes_.size();
  }
  uint64_t tellg() override { return at_; }
  void seekg(uint64_t pos) override { at_ = pos; }

 private:
  const std::vector<unsigned char>& bytes_;
  uint64_t at_ = 0;
};

// Reads from `bytes` when given, else from the file at `path` (which names it in messages).
ExrImage read(const std::string& path, bool with_pixels, const std::vector<unsigned char>* bytes = nullptr) {
  ExrImage image;
  try {
    std::unique_ptr<MemoryStream> stream;
    if (bytes) {
      std::istringstream in(std::string(bytes->begin(), bytes->end()));
      scan_exr_headers(in, bytes->size(), path);
      stream = std::make_unique<MemoryStream>(*bytes, path);
    } else {
      std::ifstream in(path, std::ios::binary | std::ios::ate);
      if (!in) throw InputError(path, "", "cannot open for reading");
      const uint64_t size = uint64_t(in.tellg());
      in.seekg(0);
      scan_exr_headers(in, size, path);
    }
    std::unique_ptr<Imf::MultiPartInputFile> opened =
        stream ? std::make_unique<Imf::MultiPartInputFile>(*stream) : std::make_unique<Imf::MultiPartInputFile>(path.c_str());
    Imf::MultiPartInputFile& file = *opened;
    for (int p = 0; p < file.parts(); ++p) {
      const Imf::Header& header = file.header(p);
      const PixelWindow dw = window(header.dataWindow(), path, "dataWindow");
      if (p == 0) {
        image.display = window(header.displayWindow(), path, "displayWindow");
        image.data = dw;
        image.multipart = file.parts() > 1;
        switch (header.compression()) {
          case Imf::NO_COMPRESSION: image.compression = ExrCompression::None; break;
          case Imf::PIZ_COMPRESSION: image.compression = ExrCompression::Piz; break;
          case Imf::DWAA_COMPRESSION: image.compression = ExrCompression::Dwaa; break;
          default: image.compression = ExrCompression::Zip; break;
        }
        for (auto it = header.begin(); it != header.end(); ++it) {
          // The required attributes describe the file's layout, which ExrImage holds itself.
          static const std::set<std::string> layout = {"channels", "compression", "dataWindow", "displayWindow",
                                                       "lineOrder", "pixelAspectRatio", "screenWindowCenter",
                                                       "screenWindowWidth", "name", "type", "version", "chunkCount"};
          if (layout.count(it.name())) continue;
          const Imf::Attribute& a = it.attribute();
          if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a)) image.attributes.push_back({it.name(), s->value()});
          else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a)) image.attributes.push_back({it.name(), i->value()});
          else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a)) image.attributes.push_back({it.name(), d->value()});
          else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a)) image.attributes.push_back({it.name(), double(f->value())});
          else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&a)) {
            ExrMatrix v;
            for (int r = 0; r < 4; ++r)
              for (int c = 0; c < 4; ++c) v[size_t(4 * r + c)] = m->value()[r][c];
            image.attributes.push_back({it.name(), v});
          }
        }
      } else if (!(dw == image.data)) {
        throw InputError(path, "part " + std::to_string(p), "its data window differs from the first part's");
      }
      if (header.hasTileDescription() && header.hasType() && header.type() != Imf::SCANLINEIMAGE)
        throw InputError(path, "part " + std::to_string(p), "only scanline images can be read");
      const size_t width = size_t(dw.width()), pixels = width * size_t(dw.height());
      if (pixels > (size_t(1) << 31)) throw InputError(path, "dataWindow", "too large");
      Imf::FrameBuffer fb;
      const size_t first = image.channels.size();
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
          throw InputError(path, std::string("channel ") + it.name(), "subsampled channels are not supported");
        ExrChannel c;
        c.name = it.name();
        c.type = it.channel().type == Imf::UINT ? ExrPixelType::Uint
                 : it.channel().type == Imf::HALF ? ExrPixelType::Half
                                                  : ExrPixelType::Float;
        image.channels.push_back(std::move(c));
      }
      if (!with_pixels) continue;
      require_memory(uint64_t(pixels) * 4 * (image.channels.size() - first), path + ": part " + std::to_string(p) + "'s pixels");
      for (size_t i = first; i < image.channels.size(); ++i) {
        ExrChannel& c = image.channels[i];
        char* base;
        if (c.type == ExrPixelType::Uint) {
          c.bits.assign(pixels, 0);
          base = reinterpret_cast<char*>(c.bits.data());
        } else {
          c.values.assign(pixels, 0.0f);
          base = reinterpret_cast<char*>(c.values.data());
        }
        fb.insert(c.name, Imf::Slice::Make(c.type == ExrPixelType::Uint ? Imf::UINT : Imf::FLOAT, base,
                                           header.dataWindow(), 4, 4 * width));
      }
      Imf::InputPart part(file, p);
      part.setFrameBuffer(fb);
      part.readPixels(dw.y0, dw.y1 - 1);
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "", std::string("cannot read EXR: ") + e.what());
  }
  return image;
}

}  // namespace

ExrImage read_exr(const std::string& path) { return read(path, true); }

ExrImage read_exr_header(const std::string& path) { return read(path, false); }

ExrImage read_exr_from_memory(const std::vector<unsigned char>& bytes, const std::string& name) {
  return read(name, true, &bytes);
}

}  // namespace prism
