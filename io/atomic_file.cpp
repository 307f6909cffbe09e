#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <filesystem>
#include <system_error>

#include "io/errors.h"

namespace prism {

namespace fs = std::filesystem;

namespace {

fs::path checked_directory(const std::string& target) {
  const fs::path p(target);
  if (p.filename().empty()) throw OutputError(target, "output path names no file");
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw OutputError(target, "output path is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw OutputError(target, "output directory '" + dir.string() + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw OutputError(target, "output directory '" + dir.string() + "' is not writable");
  return dir;
}

}  // namespace

void check_output_path(const std::string& target) { checked_directory(target); }

AtomicFile::AtomicFile(const std::string& target) : target_(target) {
  const fs::path p(target);
  const fs::path dir = checked_directory(target);
  static std::atomic<unsigned> counter{0};
  // Built by appending: GCC 12 misreports "." + std::string as an overlapping memcpy (-Wrestrict).
  std::string name(".");
  name += p.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
  temp_ = (dir / name).string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void write_file_atomically(const std::string& target, const std::string& contents) {
  AtomicFile out(target);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << contents;
    if (!f.flush()) throw OutputError(target, "cannot write");
  }
  out.commit();
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw OutputError(target_, "cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

}  // namespace prism
