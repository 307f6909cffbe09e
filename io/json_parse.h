// Parsing JSON text (scenes, job and batch files) with every parser failure as an InputError.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace prism {

// Parses `text`; any failure of nlohmann's parser (a syntax error, or a number too large for a
// double, which it reports as out_of_range) throws InputError naming `file` with the position:
// "file: not valid JSON: parse error at line 2, column 9: ...".
nlohmann::json parse_json(const std::string& text, const std::string& file);

}  // namespace prism
