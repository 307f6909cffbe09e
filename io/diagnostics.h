// Diagnostics: warnings from loading, each distinct message kept once with a count of occurrences.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/errors.h"

namespace prism {

class Diagnostics {
 public:
  // With strict set, content that would be replaced by a stand-in (a missing or undecodable
  // texture) is an error instead.
  bool strict = false;

  // Reports that `element` of `file` cannot be used for `reason` and `stand_in` replaces it: a
  // warning, or an InputError when strict.
  void substitute(const std::string& file, const std::string& element, const std::string& reason,
                  const std::string& stand_in) {
    if (strict) throw InputError(file, element, reason + " (--strict)");
    warn(element + ": " + reason + "; " + stand_in);
  }

  // Records a warning; repeats of the same text are counted, not repeated.
  void warn(const std::string& message) {
    auto [it, inserted] = counts_.try_emplace(message, 0);
    if (inserted) order_.push_back(message);
    ++it->second;
  }

  // One line per distinct warning, in first-seen order, with "(N times)" when repeated.
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    for (const auto& m : order_) {
      const int n = counts_.at(m);
      out.push_back(n > 1 ? m + " (" + std::to_string(n) + " times)" : m);
    }
    return out;
  }
  bool empty() const { return order_.empty(); }
  bool contains(const std::string& fragment) const {
    for (const auto& m : order_)
      if (m.find(fragment) != std::string::npos) return true;
    return false;
  }

 private:
  std::map<std::string, int> counts_;
  std::vector<std::string> order_;
};

}  // namespace prism
