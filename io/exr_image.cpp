#include "io/exr_image.h"

namespace prism {

std::optional<ExrCompression> parse_exr_compression(const std::string& name) {
  if (name == "none") return ExrCompression::None;
  if (name == "zip") return ExrCompression::Zip;
  if (name == "piz") return ExrCompression::Piz;
  if (name == "dwaa") return ExrCompression::Dwaa;
  return std::nullopt;
}

const ExrChannel* ExrImage::find(const std::string& name) const {
  for (const ExrChannel& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

const ExrAttribute* ExrImage::attribute(const std::string& name) const {
  for (const ExrAttribute& a : attributes)
    if (a.first == name) return &a;
  return nullptr;
}

}  // namespace prism
