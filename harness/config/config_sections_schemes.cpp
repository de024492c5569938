#include "config/config_sections.h"

#include "error.h"
#include "number_text.h"
#include "schemes/registry.h"

namespace lb {

using nlohmann::json;

// Parameters named <x>min / <x>max bound a range whose width divides (distance falloff): an empty
// range is rejected for every scheme alike, so one scheme cannot accept what another refuses.
static void requireRanges(const ConfigReader& r, const SchemeInfo& info, const ParamValues& pv, const std::string& ptr) {
  for (auto& p : info.params) {
    const size_t n = p.name.size();
    if (n < 4 || p.name.compare(n - 3, 3, "min") != 0) continue;
    const std::string hi = p.name.substr(0, n - 3) + "max";
    auto lo = pv.find(p.name), up = pv.find(hi);
    if (lo == pv.end() || up == pv.end()) continue;
    if (!(lo->second < up->second)) {
      r.fail(ptr, info.name + ": " + p.name + " (" + numberText(lo->second) + ") must be less than " + hi + " (" +
                      numberText(up->second) + ")");
    }
  }
}

static SchemeEntry parseScheme(const ConfigReader& r, const json& s, const std::string& ptr) {
  SchemeEntry e;
  json params = json::object();
  if (s.is_string()) {
    e.name = s.get<std::string>();
  } else {
    r.onlyKeys(s, ptr, {"name", "params"});
    if (!s.contains("name")) r.fail(ptr, "missing 'name'");
    e.name = r.string(s["name"], ptr + "/name");
    if (s.contains("params")) params = s["params"];
  }
  const Scheme* scheme = findScheme(e.name);
  if (!scheme)
    r.fail(ptr + (s.is_string() ? "" : "/name"), "unknown scheme '" + printable(e.name) + "' (known: " + schemeNames() + ")");
  if (!params.is_object()) r.fail(ptr + "/params", "expected an object of parameter values");
  // Cartesian product of the listed values of each parameter.
  e.variants = {ParamValues{}};
  for (auto& [k, v] : params.items()) {
    std::string pp = ptr + "/params/" + k;
    std::vector<double> values;
    if (v.is_array()) {
      for (size_t i = 0; i < v.size(); ++i) values.push_back(r.number(v[i], pp + "/" + std::to_string(i), -1e30, 1e30));
      if (values.empty()) r.fail(pp, "empty list");
    } else {
      values.push_back(r.number(v, pp, -1e30, 1e30));
    }
    std::vector<ParamValues> next;
    for (auto& base : e.variants)
      for (double d : values) {
        ParamValues pv = base;
        pv[k] = d;
        try {
          resolveParams(scheme->info(), {{k, d}});
        } catch (const InputError& err) {
          r.fail(pp, err.what());
        }
        next.push_back(pv);
      }
    e.variants = next;
  }
  // Cross-parameter checks (e.g. dmin < dmax) need every parameter of a variant.
  for (auto& pv : e.variants) {
    ParamValues full;
    try {
      full = resolveParams(scheme->info(), pv);
      scheme->validate(full);
    } catch (const InputError& err) {
      r.fail(ptr + "/params", err.what());
    }
    requireRanges(r, scheme->info(), full, ptr + "/params");
  }
  return e;
}

void parseSchemeSection(const ConfigReader& r, const json& j, Config& c) {
  if (!j.contains("schemes") || !j["schemes"].is_array() || j["schemes"].empty())
    r.fail("/schemes", "expected a non-empty array of schemes (known: " + schemeNames() + ")");
  for (size_t i = 0; i < j["schemes"].size(); ++i)
    c.schemes.push_back(parseScheme(r, j["schemes"][i], "/schemes/" + std::to_string(i)));
}

}  // namespace lb
