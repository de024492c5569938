#pragma once
// Parses a JSON config text strictly: syntax errors, duplicate keys (nlohmann would silently keep
// the last) and absurd nesting all throw lb::InputError "file:line[:col]: ...", naming the JSON
// pointer where there is one.
#include <nlohmann/json.hpp>
#include <string>

namespace lb {
nlohmann::json parseJsonStrict(const std::string& text, const std::string& file);
}  // namespace lb
