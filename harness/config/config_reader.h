#pragma once
// Reads fields of a config's JSON with the error form every config message takes:
// "file:line: field '/json/pointer': problem" (tests pin these messages).
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "did_you_mean.h"
#include "error.h"
#include "number_text.h"

namespace lb {

struct ConfigReader {
  std::string file;
  std::map<std::string, int> lines;

  [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const {
    auto it = lines.find(ptr);
    std::string where = file + (it != lines.end() ? ":" + std::to_string(it->second) : "");
    throw InputError(where + ": field '" + (ptr.empty() ? "/" : ptr) + "': " + msg);
  }
  void onlyKeys(const nlohmann::json& obj, const std::string& ptr, const std::set<std::string>& allowed) const {
    if (!obj.is_object()) fail(ptr, "expected an object");
    for (auto& [k, v] : obj.items())
      if (!allowed.count(k)) {
        std::string list;
        for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(ptr + "/" + printable(k),
             "unknown key (allowed: " + list + ")" + didYouMean(k, {allowed.begin(), allowed.end()}));
      }
  }
  double number(const nlohmann::json& v, const std::string& ptr, double lo, double hi) const {
    if (!v.is_number()) fail(ptr, "expected a number, got " + printable(v.dump()));
    double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) {
      fail(ptr, numberText(d) + " is outside [" + numberText(lo) + ", " + numberText(hi) + "]");
    }
    return d;
  }
  int integer(const nlohmann::json& v, const std::string& ptr, int lo, int hi) const {
    double d = number(v, ptr, lo, hi);
    if (d != std::floor(d)) fail(ptr, "expected an integer, got " + v.dump());
    return int(d);
  }
  std::string string(const nlohmann::json& v, const std::string& ptr) const {
    if (!v.is_string()) fail(ptr, "expected a string, got " + printable(v.dump()));
    return v.get<std::string>();
  }
};

// p relative to base (the config's folder); absolute and empty paths as they are.
std::string resolvePath(const std::string& base, const std::string& p);
// A file a config names: it must exist and be a regular file (a directory opens, then reads as empty).
std::string inputFile(const ConfigReader& r, const nlohmann::json& v, const std::string& ptr, const std::string& base,
                      const char* what);

}  // namespace lb
