// Diagnostics: warnings from loading, each distinct message kept once with a count of occurrences.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace prism {

class Diagnostics {
 public:
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
