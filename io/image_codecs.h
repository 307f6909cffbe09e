// ImageCodecs: image decoding and PNG encoding, in a module loaded only when an image is met.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

namespace prism {

// OpenImageIO lives in its own module (libprism_image_codecs.so, beside the prism binary) that is
// opened on first use: linked into prism, its ~250 shared libraries cost every process about 0.35 s
// of dynamic loading, although most renders read no image and write no PNG.
class ImageCodecs {
 public:
  // How samples are read: as floats (any image), or as their own 8-bit or 16-bit codes or half
  // floats (only images whose every channel is stored so: the read is then exact), or as RGBE
  // texels (core/rgbe.h; 3 channels of a Radiance .hdr file), which read() refuses unless every
  // texel turns back into exactly the floats the file decodes to.
  enum class Samples { Float, Uint8, Uint16, Half, Rgbe };
  struct Info {
    int width = 0, height = 0, channels = 0;
    bool is_float = false;  // FLOAT, HALF or DOUBLE samples: linear data, not sRGB-encoded
    bool is_8bit = false;   // every channel UINT8: Samples::Uint8 reads them exactly
    bool is_16bit = false;  // every channel UINT16: Samples::Uint16 reads them exactly
    bool is_half = false;   // every channel HALF: Samples::Half reads them exactly
    bool is_rgbe = false;   // a Radiance .hdr file: Samples::Rgbe may read it
  };
  // An opened image whose header is read; read() decodes its first `channels` channels.
  class Input {
   public:
    virtual ~Input() = default;
    virtual Info info() const = 0;
    // Fills width x height x channels samples of the given kind (floats, or 8- or 16-bit values); false with
    // `error` set when the data is bad.
    virtual bool read(int channels, Samples kind, void* texels, std::string& error) = 0;
  };

  virtual ~ImageCodecs() = default;
  // Null with `error` set when the bytes or the file are not an image it reads.
  virtual std::unique_ptr<Input> open_memory(const unsigned char* data, size_t size, std::string& error) const = 0;
  virtual std::unique_ptr<Input> open_file(const std::string& path, std::string& error) const = 0;
  // Writes 8-bit RGB pixels as a PNG file at `path` (whatever its name ends with).
  virtual bool write_png(const std::string& path, int width, int height, const unsigned char* rgb,
                         std::string& error) const = 0;
};

// The module, opened once per process. Throws std::runtime_error saying where it looked and why
// it failed when it cannot be opened.
const ImageCodecs& image_codecs();

}  // namespace prism

// The module's one export: its codecs, which live as long as the process.
extern "C" const prism::ImageCodecs* prism_image_codecs_v4();
