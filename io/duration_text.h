// Durations as users write them: "90", "90s", "2.5m", "1h30m", "250ms".
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace prism {

// Seconds in `text`: numbers each followed by a unit (ms, s, m, h; a lone number is seconds).
// nullopt for anything else or a negative or non-finite total.
inline std::optional<double> parse_duration(const std::string& text) {
  const char* p = text.c_str();
  double total = 0;
  bool any = false;
  while (*p) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v) || v < 0 || *p == '+' || *p == '-' || std::isspace(static_cast<unsigned char>(*p)))
      return std::nullopt;
    p = end;
    double unit = 1;
    if (p[0] == 'm' && p[1] == 's') unit = 1e-3, p += 2;
    else if (*p == 's') ++p;
    else if (*p == 'm') unit = 60, ++p;
    else if (*p == 'h') unit = 3600, ++p;
    else if (*p != '\0' || any) return std::nullopt;  // a bare number only on its own
    total += v * unit;
    any = true;
  }
  if (!any || !std::isfinite(total)) return std::nullopt;
  return total;
}

}  // namespace prism
