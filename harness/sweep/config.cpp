#include "sweep/config.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "error.h"
#include "schemes/registry.h"
#include "sweep/json_lines.h"

namespace lb {
namespace {

using nlohmann::json;

struct Reader {
  std::string file;
  std::map<std::string, int> lines;

  [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const {
    auto it = lines.find(ptr);
    std::string where = file + (it != lines.end() ? ":" + std::to_string(it->second) : "");
    throw InputError(where + ": field '" + (ptr.empty() ? "/" : ptr) + "': " + msg);
  }
  void onlyKeys(const json& obj, const std::string& ptr, const std::set<std::string>& allowed) const {
    if (!obj.is_object()) fail(ptr, "expected an object");
    for (auto& [k, v] : obj.items())
      if (!allowed.count(k)) {
        std::string list;
        for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(ptr + "/" + k, "unknown key (allowed: " + list + ")");
      }
  }
  double number(const json& v, const std::string& ptr, double lo, double hi) const {
    if (!v.is_number()) fail(ptr, "expected a number, got " + v.dump());
    double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) {
      std::ostringstream s;
      s << d << " is outside [" << lo << ", " << hi << "]";
      fail(ptr, s.str());
    }
    return d;
  }
  int integer(const json& v, const std::string& ptr, int lo, int hi) const {
    double d = number(v, ptr, lo, hi);
    if (d != std::floor(d)) fail(ptr, "expected an integer, got " + v.dump());
    return int(d);
  }
  std::string string(const json& v, const std::string& ptr) const {
    if (!v.is_string()) fail(ptr, "expected a string, got " + v.dump());
    return v.get<std::string>();
  }
};

std::string resolvePath(const std::string& base, const std::string& p) {
  if (p.empty() || p[0] == '/' || base.empty()) return p;
  return base + "/" + p;
}

std::vector<TerrainSpec> parseTerrain(const Reader& r, const json& t, const std::string& ptr, const std::string& base) {
  r.onlyKeys(t, ptr, {"type", "file", "size", "seed", "extent", "height_scale", "width", "height"});
  TerrainSpec spec;
  if (t.contains("type")) spec.type = r.string(t["type"], ptr + "/type");
  static const std::set<std::string> kTypes = {"procedural", "hgt", "png16", "r16", "r32f"};
  if (!kTypes.count(spec.type)) r.fail(ptr + "/type", "'" + spec.type + "' is not one of procedural, hgt, png16, r16, r32f");
  if (spec.type != "procedural") {
    if (!t.contains("file")) r.fail(ptr, "terrain type '" + spec.type + "' needs a 'file'");
    spec.file = resolvePath(base, r.string(t["file"], ptr + "/file"));
    if (!std::ifstream(spec.file)) r.fail(ptr + "/file", "cannot open '" + spec.file + "'");
    spec.heightScale = 1.0f;
  }
  if (t.contains("size")) spec.size = r.integer(t["size"], ptr + "/size", 2, 16385);
  if (t.contains("extent")) spec.extent = float(r.number(t["extent"], ptr + "/extent", 1e-3, 1e9));
  if (t.contains("height_scale")) spec.heightScale = float(r.number(t["height_scale"], ptr + "/height_scale", 0, 1e9));
  if (t.contains("width")) spec.rawWidth = r.integer(t["width"], ptr + "/width", 2, 65536);
  if (t.contains("height")) spec.rawHeight = r.integer(t["height"], ptr + "/height", 2, 65536);
  if ((spec.type == "r16" || spec.type == "r32f") && (spec.rawWidth == 0 || spec.rawHeight == 0))
    r.fail(ptr, "raw terrain needs 'width' and 'height'");
  std::vector<TerrainSpec> out;
  if (t.contains("seed") && t["seed"].is_array()) {
    for (size_t i = 0; i < t["seed"].size(); ++i) {
      spec.seed = uint32_t(r.integer(t["seed"][i], ptr + "/seed/" + std::to_string(i), 0, 2147483647));
      out.push_back(spec);
    }
    if (out.empty()) r.fail(ptr + "/seed", "empty list");
  } else {
    if (t.contains("seed")) spec.seed = uint32_t(r.integer(t["seed"], ptr + "/seed", 0, 2147483647));
    out.push_back(spec);
  }
  return out;
}

SchemeEntry parseScheme(const Reader& r, const json& s, const std::string& ptr) {
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
  if (!scheme) r.fail(ptr + (s.is_string() ? "" : "/name"), "unknown scheme '" + e.name + "' (known: " + schemeNames() + ")");
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
    try {
      scheme->validate(resolveParams(scheme->info(), pv));
    } catch (const InputError& err) {
      r.fail(ptr + "/params", err.what());
    }
  }
  return e;
}

}  // namespace

Config parseConfig(const std::string& text, const std::string& file, const std::string& baseDir) {
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
    throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(col) + ": invalid JSON: " + e.what());
  }
  Reader r{file, jsonLineMap(text)};
  r.onlyKeys(j, "", {"name", "device", "resolution", "resolutions", "grid", "fps", "warmup_frames", "max_frames",
                     "repetitions", "case_timeout_s", "terrain", "terrains", "path", "paths", "schemes", "images", "measure", "match",
                     "description", "timing", "calibration"});
  Config c;
  c.file = file;
  c.raw = j;
  if (j.contains("name")) c.name = r.string(j["name"], "/name");
  if (c.name.empty() || c.name.find_first_of("/\\ ") != std::string::npos)
    r.fail("/name", "must be a non-empty name without '/', '\\' or spaces");
  if (j.contains("device")) c.device = r.string(j["device"], "/device");
  for (const char* key : {"resolution", "resolutions"}) {
    if (!j.contains(key)) continue;
    const json& v = j[key];
    std::string ptr = std::string("/") + key;
    auto pair = [&](const json& p, const std::string& pp) {
      if (!p.is_array() || p.size() != 2) r.fail(pp, "expected [width, height]");
      int w = r.integer(p[0], pp + "/0", 16, 8192);
      int h = r.integer(p[1], pp + "/1", 16, 8192);
      return std::make_pair(w, h);
    };
    c.resolutions.clear();
    if (v.is_array() && !v.empty() && v[0].is_array()) {
      for (size_t i = 0; i < v.size(); ++i) c.resolutions.push_back(pair(v[i], ptr + "/" + std::to_string(i)));
    } else {
      c.resolutions.push_back(pair(v, ptr));
    }
  }
  if (j.contains("grid")) c.grid = r.integer(j["grid"], "/grid", 1, 1024);
  if (j.contains("fps")) c.fps = r.number(j["fps"], "/fps", 1, 1000);
  if (j.contains("warmup_frames")) c.warmupFrames = r.integer(j["warmup_frames"], "/warmup_frames", 0, 100000);
  if (j.contains("max_frames")) c.maxFrames = r.integer(j["max_frames"], "/max_frames", 0, 10000000);
  if (j.contains("case_timeout_s")) c.caseTimeoutS = r.number(j["case_timeout_s"], "/case_timeout_s", 0, 1e7);
  if (j.contains("repetitions")) c.repetitions = r.integer(j["repetitions"], "/repetitions", 1, 1000);
  if (j.contains("terrain")) {
    auto t = parseTerrain(r, j["terrain"], "/terrain", baseDir);
    c.terrains.insert(c.terrains.end(), t.begin(), t.end());
  }
  if (j.contains("terrains")) {
    if (!j["terrains"].is_array()) r.fail("/terrains", "expected an array");
    for (size_t i = 0; i < j["terrains"].size(); ++i) {
      auto t = parseTerrain(r, j["terrains"][i], "/terrains/" + std::to_string(i), baseDir);
      c.terrains.insert(c.terrains.end(), t.begin(), t.end());
    }
  }
  if (c.terrains.empty()) c.terrains.push_back(TerrainSpec{});
  auto addPath = [&](const json& p, const std::string& ptr) {
    std::string path = resolvePath(baseDir, r.string(p, ptr));
    if (!std::ifstream(path)) r.fail(ptr, "cannot open camera path '" + path + "'");
    c.paths.push_back(path);
  };
  if (j.contains("path")) addPath(j["path"], "/path");
  if (j.contains("paths")) {
    if (!j["paths"].is_array()) r.fail("/paths", "expected an array of CSV files");
    for (size_t i = 0; i < j["paths"].size(); ++i) addPath(j["paths"][i], "/paths/" + std::to_string(i));
  }
  if (c.paths.empty()) r.fail("", "no camera path: set 'paths' to a list of CSV files");
  if (!j.contains("schemes") || !j["schemes"].is_array() || j["schemes"].empty())
    r.fail("/schemes", "expected a non-empty array of schemes (known: " + schemeNames() + ")");
  for (size_t i = 0; i < j["schemes"].size(); ++i)
    c.schemes.push_back(parseScheme(r, j["schemes"][i], "/schemes/" + std::to_string(i)));
  if (j.contains("images")) {
    const json& im = j["images"];
    r.onlyKeys(im, "/images", {"frames", "modes"});
    if (im.contains("frames")) {
      if (!im["frames"].is_array()) r.fail("/images/frames", "expected an array of frame indices");
      for (size_t i = 0; i < im["frames"].size(); ++i)
        c.images.frames.push_back(r.integer(im["frames"][i], "/images/frames/" + std::to_string(i), -1000000, 1000000));
    }
    c.images.modes = {"shaded"};
    if (im.contains("modes")) {
      c.images.modes.clear();
      for (size_t i = 0; i < im["modes"].size(); ++i) {
        std::string m = r.string(im["modes"][i], "/images/modes/" + std::to_string(i));
        if (m != "shaded" && m != "heatmap" && m != "wireframe" && m != "error" && m != "cracks")
          r.fail("/images/modes/" + std::to_string(i),
                 "'" + m + "' is not one of shaded, heatmap, wireframe, error, cracks");
        c.images.modes.push_back(m);
      }
    }
  }
  // Timing modes and clock-control calibration (issue 13; see sweep/timing_spec.h).
  if (j.contains("timing")) {
    const json& t = j["timing"];
    if (!t.is_array() || t.empty()) r.fail("/timing", "expected a non-empty array of timing modes (shaded, depth, frontend)");
    c.timing.modes.clear();
    for (size_t i = 0; i < t.size(); ++i) {
      std::string m = r.string(t[i], "/timing/" + std::to_string(i));
      if (m != "shaded" && m != "depth" && m != "frontend")
        r.fail("/timing/" + std::to_string(i), "unknown timing mode '" + m + "' (shaded, depth, frontend)");
      if (std::find(c.timing.modes.begin(), c.timing.modes.end(), m) != c.timing.modes.end())
        r.fail("/timing/" + std::to_string(i), "timing mode '" + m + "' listed twice");
      c.timing.modes.push_back(m);
    }
    if (std::find(c.timing.modes.begin(), c.timing.modes.end(), "shaded") == c.timing.modes.end())
      r.fail("/timing", "must include \"shaded\" (the case's gpu_ms is the shaded time)");
  }
  if (j.contains("calibration")) {
    const json& k = j["calibration"];
    if (k.is_boolean()) {
      c.timing.calibrate = k.get<bool>();
    } else {
      r.onlyKeys(k, "/calibration", {"level", "frames", "max_tries"});
      c.timing.calibrate = true;
      if (k.contains("level")) c.timing.level = r.integer(k["level"], "/calibration/level", 1, 64);
      if (k.contains("frames")) c.timing.frames = r.integer(k["frames"], "/calibration/frames", 1, 1000);
      if (k.contains("max_tries")) c.timing.maxTries = r.integer(k["max_tries"], "/calibration/max_tries", 3, 1000);
    }
  }
  if (j.contains("measure")) {
    const json& me = j["measure"];
    r.onlyKeys(me, "/measure", {"every", "passes", "diff_threshold"});
    c.measure.every = me.contains("every") ? r.integer(me["every"], "/measure/every", 0, 1000000) : 10;
    if (me.contains("passes")) {
      if (!me["passes"].is_array()) r.fail("/measure/passes", "expected an array of pass names");
      c.measure.passes.clear();
      for (size_t i = 0; i < me["passes"].size(); ++i) {
        std::string p = r.string(me["passes"][i], "/measure/passes/" + std::to_string(i));
        if (!allMeasurePasses().count(p))
          r.fail("/measure/passes/" + std::to_string(i),
                 "'" + p + "' is not one of histogram, error, image, cracks, popping, surplus");
        c.measure.passes.insert(p);
      }
    }
    if (me.contains("diff_threshold"))
      c.measure.diffThreshold = r.integer(me["diff_threshold"], "/measure/diff_threshold", 0, 255);
  }
  if (j.contains("match")) {
    const json& m = j["match"];
    r.onlyKeys(m, "/match", {"metric", "value", "frames", "iterations"});
    if (!m.contains("metric") || !m.contains("value")) r.fail("/match", "needs 'metric' and 'value'");
    c.match.metric = r.string(m["metric"], "/match/metric");
    if (c.match.metric != "triangles" && c.match.metric != "err_mean_px")
      r.fail("/match/metric", "'" + c.match.metric + "' is not one of triangles, err_mean_px");
    c.match.value = r.number(m["value"], "/match/value", 0, 1e12);
    if (m.contains("frames")) c.match.frames = r.integer(m["frames"], "/match/frames", 1, 10000);
    if (m.contains("iterations")) c.match.iterations = r.integer(m["iterations"], "/match/iterations", 1, 60);
  }
  return c;
}

Config loadConfig(const std::string& file) {
  std::ifstream f(file);
  if (!f) throw InputError("cannot open config '" + file + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  auto slash = file.find_last_of('/');
  return parseConfig(ss.str(), file, slash == std::string::npos ? "." : file.substr(0, slash));
}

std::string terrainLabel(const TerrainSpec& t) {
  if (t.type == "procedural") return "proc" + std::to_string(t.size) + "s" + std::to_string(t.seed);
  auto slash = t.file.find_last_of('/');
  std::string stem = t.file.substr(slash == std::string::npos ? 0 : slash + 1);
  return stem.substr(0, stem.find('.'));
}

static std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<Case> expandCases(const Config& config) {
  std::vector<Case> cases;
  for (auto& t : config.terrains)
    for (auto& path : config.paths)
      for (auto& res : config.resolutions)
        for (auto& s : config.schemes)
          for (auto& params : s.variants) {
            Case c{"", s.name, params, t, terrainLabel(t), path, res.first, res.second};
            auto slash = path.find_last_of('/');
            std::string stem = path.substr(slash == std::string::npos ? 0 : slash + 1);
            stem = stem.substr(0, stem.find('.'));
            c.id = s.name;
            for (auto& [k, v] : params) c.id += "-" + k + formatNumber(v);
            c.id += "_" + c.terrainLabel + "_" + stem + "_" + std::to_string(res.first) + "x" + std::to_string(res.second);
            if (config.match.on()) c.id += "_match-" + config.match.metric + formatNumber(config.match.value);
            cases.push_back(c);
          }
  return cases;
}

}  // namespace lb
