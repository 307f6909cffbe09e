#include "io/json_parse.h"

#include "io/errors.h"

namespace prism {

nlohmann::json parse_json(const std::string& text, const std::string& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    std::string what = e.what();  // "[json.exception.parse_error.101] parse error at line 1, ..."
    if (auto close = what.find("] "); close != std::string::npos) what = what.substr(close + 2);
    throw InputError(file, "", "not valid JSON: " + what);
  }
}

}  // namespace prism
