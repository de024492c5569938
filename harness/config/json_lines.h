#pragma once
// Maps each JSON pointer of a (valid) JSON text to the line its value starts on, so config
// errors can name file, line and field. nlohmann/json keeps no positions for values.
#include <map>
#include <string>

namespace lb {
std::map<std::string, int> jsonLineMap(const std::string& text);
}  // namespace lb
