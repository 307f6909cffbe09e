#include "core/aov.h"

#include <stdexcept>

namespace prism {

const std::vector<std::string>& aov_names() {
  static const std::vector<std::string> names = {"albedo",   "normal",   "depth",     "position",    "emission",
                                                 "direct",   "indirect", "variance",  "spp",         "object_id",
                                                 "material_id", "crypto_object", "crypto_material"};
  return names;
}

const std::string& aov_name(Aov a) { return aov_names()[size_t(a)]; }

AovSet parse_aovs(const std::string& list) {
  AovSet set;
  size_t start = 0;
  while (start <= list.size()) {
    size_t end = list.find(',', start);
    if (end == std::string::npos) end = list.size();
    std::string item = list.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.erase(item.begin());
    while (!item.empty() && item.back() == ' ') item.pop_back();
    start = end + 1;
    if (item.empty()) continue;
    if (item == "all") {
      for (size_t i = 0; i < size_t(Aov::Count); ++i) set.add(Aov(i));
      continue;
    }
    bool known = false;
    for (size_t i = 0; i < aov_names().size(); ++i)
      if (aov_names()[i] == item) {
        set.add(Aov(i));
        known = true;
      }
    if (!known) {
      std::string names;
      for (const std::string& n : aov_names()) names += (names.empty() ? "" : ", ") + n;
      throw std::invalid_argument("unknown AOV '" + item + "'; known: " + names + ", all");
    }
  }
  return set;
}

}  // namespace prism
