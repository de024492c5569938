#include "config/json_strict.h"

#include <set>
#include <vector>

#include "config/json_lines.h"
#include "error.h"

namespace lb {
namespace {

using nlohmann::json;

// nlohmann keeps the last of duplicate keys; a config with two "seed"s is a mistake, so find them
// while parsing (the callback sees every key) and name the JSON pointer of the second.
// Absurd nesting is refused the same way.
struct StructureError {
  std::string pointer;
  std::string problem = "duplicate key (JSON would silently keep only the last value)";
  bool tooDeep = false;
};
constexpr int kMaxDepth = 32;

json parseTracked(const std::string& text) {
  struct Level {
    bool object = false;
    std::set<std::string> keys;
    std::string key;
    long index = -1;
  };
  std::vector<Level> stack;
  auto pointer = [&] {
    std::string p;
    for (auto& l : stack) {
      if (!l.object) {
        p += "/" + std::to_string(l.index);
        continue;
      }
      p += "/";
      for (char ch : l.key) p += ch == '~' ? "~0" : ch == '/' ? "~1" : std::string(1, ch);
    }
    return p;
  };
  json::parser_callback_t cb = [&](int depth, json::parse_event_t ev, json& parsed) {
    using E = json::parse_event_t;
    // No config nests deeper than 5; the limit keeps the line scanner (recursive) bounded.
    if (depth > kMaxDepth)
      throw StructureError{pointer(), "nested deeper than " + std::to_string(kMaxDepth) + " levels", true};
    if ((ev == E::object_start || ev == E::array_start || ev == E::value) && !stack.empty() && !stack.back().object)
      ++stack.back().index;
    if (ev == E::object_start || ev == E::array_start) stack.push_back({ev == E::object_start, {}, {}, -1});
    if (ev == E::object_end || ev == E::array_end) stack.pop_back();
    if (ev == E::key) {
      stack.back().key = parsed.get<std::string>();
      if (!stack.back().keys.insert(stack.back().key).second) throw StructureError{pointer()};
    }
    return true;
  };
  return json::parse(text, cb);
}

}  // namespace

json parseJsonStrict(const std::string& text, const std::string& file) {
  // Syntax first: the line scanner that places the other errors assumes valid JSON.
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    size_t line = 1, col = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(col) +
                     ": invalid JSON: " + printable(e.what(), 200));
  } catch (const json::exception& e) {
    // e.g. out_of_range for a number past double's range (found by fuzzing); it carries no position.
    throw InputError(file + ": invalid JSON: " + printable(e.what(), 200));
  }
  try {
    parseTracked(text);
  } catch (const StructureError& d) {
    // The line scanner recurses, so it never sees text nested past the limit.
    auto lines = d.tooDeep ? std::map<std::string, int>{} : jsonLineMap(text);
    auto it = lines.find(d.pointer);
    throw InputError(file + (it != lines.end() ? ":" + std::to_string(it->second) : "") + ": field '" +
                     printable(d.pointer, 200) + "': " + d.problem);
  }
  return j;
}

}  // namespace lb
