#include "io/exr_header_scan.h"

#include <cstring>

#include "io/errors.h"

namespace prism {
namespace {

constexpr uint32_t kMagic = 20000630;           // 0x762f3101, little-endian in the file
constexpr uint32_t kTiledFlag = 0x200, kLongNamesFlag = 0x400, kDeepFlag = 0x800, kMultipartFlag = 0x1000;
constexpr int64_t kMaxLinesPerChunk = 256;     // DWAB, the largest chunk of scanlines

class Scanner {
 public:
  Scanner(std::istream& in, uint64_t size, const std::string& path) : in_(in), size_(size), path_(path) {}

  void run() {
    const uint32_t magic = u32("magic number"), version = u32("version");
    if (magic != kMagic) fail("", "not an OpenEXR file");
    if ((version & 0xff) != 2) fail("", "OpenEXR version " + std::to_string(version & 0xff) + ", expected 2");
    if (version & kDeepFlag) fail("", "deep images are not supported");
    const bool multipart = version & kMultipartFlag;
    if ((version & kTiledFlag) && !multipart) fail("", "only scanline images can be read (this one is tiled)");
    const size_t max_name = (version & kLongNamesFlag) ? 255 : 31;
    for (int part = 0;; ++part) {
      if (multipart && peek() == 0) break;  // an empty header ends the list of parts
      header(part, max_name);
      if (!multipart) break;
    }
  }

 private:
  [[noreturn]] void fail(const std::string& element, const std::string& reason) const {
    throw InputError(path_, element, reason);
  }

  uint64_t remaining() const { return size_ - at_; }

  void read(void* out, uint64_t n, const char* what) {
    if (n > remaining()) fail("", std::string("the file ends inside the header (") + what + ")");
    in_.read(static_cast<char*>(out), std::streamsize(n));
    if (!in_) fail("", std::string("cannot read the header (") + what + ")");
    at_ += n;
  }
  uint32_t u32(const char* what) {
    unsigned char b[4];
    read(b, 4, what);
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
  }
  int32_t i32(const char* what) {
    const uint32_t u = u32(what);
    int32_t v;
    std::memcpy(&v, &u, 4);
    return v;
  }
  int peek() {
    if (remaining() == 0) fail("", "the file ends inside the header");
    return in_.peek();
  }
  std::string text(size_t max, const char* what) {
    std::string s;
    for (;;) {
      char c;
      read(&c, 1, what);
      if (c == 0) return s;
      if (s.size() == max) fail("", std::string(what) + " '" + s.substr(0, 32) + "...' is longer than " + std::to_string(max) + " characters");
      s += c;
    }
  }

  void header(int part, size_t max_name) {
    const std::string element = "part " + std::to_string(part);
    for (;;) {
      const std::string name = text(max_name, "attribute name");
      if (name.empty()) return;
      const std::string type = text(max_name, "attribute type");
      const int32_t size = i32("attribute size");
      const std::string where = element + " attribute '" + name + "'";
      if (size < 0 || uint64_t(size) > remaining())
        fail(where, "declares " + std::to_string(size) + " bytes; the file has " + std::to_string(remaining()) + " left");
      if (name == "dataWindow" && type == "box2i" && size == 16) {
        const int64_t x0 = i32("dataWindow"), y0 = i32("dataWindow"), x1 = i32("dataWindow"), y1 = i32("dataWindow");
        const int64_t w = x1 - x0 + 1, h = y1 - y0 + 1;
        if (w <= 0 || h <= 0) fail(where, "is empty");
        // Every chunk of scanlines has an 8-byte entry in the offset table, which is in the file.
        if ((h + kMaxLinesPerChunk - 1) / kMaxLinesPerChunk * 8 > int64_t(size_))
          fail(where, std::to_string(h) + " lines need a larger offset table than the whole file (" +
                          std::to_string(size_) + " bytes)");
      } else if (name == "chunkCount" && type == "int" && size == 4) {
        const int64_t chunks = i32("chunkCount");
        if (chunks < 0 || chunks * 8 > int64_t(size_)) fail(where, std::to_string(chunks) + " chunks cannot fit in the file");
      } else if (name == "type" && type == "string" && size <= 16) {
        std::string value(size_t(size), '\0');
        read(value.data(), uint64_t(size), "type");
        if (value == "tiledimage" || value.rfind("deep", 0) == 0) fail(where, "only scanline images can be read (this part is " + value + ")");
      } else {
        value(type, uint64_t(size), where);
      }
    }
  }

  // OpenEXR reads a known type by its own layout, not by the declared size: a box2i is 16 bytes
  // whatever the size says, a channel list runs to its null name, a string vector holds
  // length-prefixed strings it allocates by their lengths. So each value must be exactly its
  // declared size, with every inner length inside it, or OpenEXR and this scan part ways.
  void value(const std::string& type, uint64_t size, const std::string& where) {
    static const std::pair<const char*, uint64_t> kFixed[] = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"double", 8}, {"envmap", 1},
        {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64},
        {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16},
        {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"deepImageState", 1}};
    for (const auto& [name, bytes] : kFixed)
      if (type == name) {
        if (size != bytes) fail(where, "a " + type + " is " + std::to_string(bytes) + " bytes, not " + std::to_string(size));
        return skip(size);
      }
    const uint64_t end = at_ + size;
    if (type == "chlist") {
      // Entries: name, null, then pixel type (4), pLinear (1), reserved (3), x and y sampling (8).
      for (;;) {
        if (text(255, "channel name").empty()) break;
        skip(16);
        if (at_ > end) break;
      }
    } else if (type == "preview") {
      const uint64_t w = u32("preview width"), h = u32("preview height");
      if (8 + w * h * 4 != size) fail(where, "a " + std::to_string(w) + "x" + std::to_string(h) + " preview is not " + std::to_string(size) + " bytes");
      skip(size - 8);
    } else if (type == "stringvector") {
      while (at_ < end) {
        const int32_t length = i32("string length");
        if (length < 0 || at_ + uint64_t(length) > end) fail(where, "holds a string that runs past the attribute");
        skip(uint64_t(length));
      }
    } else {
      skip(size);
    }
    if (at_ != end) fail(where, "its " + type + " value does not fill its declared " + std::to_string(size) + " bytes");
  }

  void skip(uint64_t n) {
    if (n > remaining()) fail("", "the file ends inside the header");
    in_.seekg(std::streamoff(n), std::ios::cur);
    if (!in_) fail("", "cannot read the header");
    at_ += n;
  }

  std::istream& in_;
  uint64_t size_, at_ = 0;
  const std::string& path_;
};

}  // namespace

void scan_exr_headers(std::istream& in, uint64_t file_size, const std::string& path) {
  Scanner(in, file_size, path).run();
}

}  // namespace prism
