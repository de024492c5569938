#include "config/config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/case_identity.h"
#include "config/config_sections.h"
#include "config/json_lines.h"
#include "config/json_strict.h"
#include "did_you_mean.h"
#include "error.h"
#include "number_text.h"
#include "schemes/plugins.h"
#include "schemes/registry.h"
#include "terrain/gdal_loader.h"
#include "terrain/generators.h"
#include "terrain/terrain_cache.h"

namespace lb {

using nlohmann::json;

static bool isRawTerrain(const TerrainSpec& s) {
  return s.type == "r16" || s.type == "r32f";
}
static bool isProceduralTerrain(const TerrainSpec& s) {
  return s.type == "procedural" || isGeneratedTerrain(s.type);
}

// The terrain's type, and no field that type does not read.
static void parseTerrainType(const ConfigReader& r, const json& t, const std::string& ptr, TerrainSpec& spec) {
  if (t.contains("type")) spec.type = r.string(t["type"], ptr + "/type");
  static const std::set<std::string> kTypes = {"procedural", "hgt",   "png16", "r16",   "r32f",  "gdal",
                                               "spikes",     "cliff", "flat",  "voids", "canyon"};
  if (!kTypes.count(spec.type))
    r.fail(ptr + "/type",
           "'" + printable(spec.type) +
               "' is not one of procedural, hgt, png16, r16, r32f, gdal, spikes, cliff, flat, voids, canyon");
  const bool gdal = spec.type == "gdal";
  if (gdal && !haveGdal())
    r.fail(ptr + "/type",
           "this build has no GDAL (configured with -DLODBENCH_GDAL=OFF, the default with "
           "LODBENCH_STATIC_RUNTIME): build with GDAL, or convert the DEM to r32f");
  // A field the type does not read would be silently ignored: reject it instead.
  const bool raw = isRawTerrain(spec), procedural = isProceduralTerrain(spec);
  auto reason = [](const std::string& k) {
    if (k == "file") return "generated terrains are not read from a file";
    if (k == "size" || k == "seed") return "only generated terrains take a size and seed";
    if (k == "band" || k == "window" || k == "overview") return "only gdal rasters take a band, window and overview";
    return "only r16 and r32f take a width and height; other files carry their size";
  };
  for (const std::string k : {"file", "size", "seed", "width", "height", "band", "window", "overview"}) {
    const bool used = k == "file"                       ? !procedural
                      : (k == "size" || k == "seed")    ? procedural
                      : (k == "width" || k == "height") ? raw
                                                        : gdal;
    if (t.contains(k) && !used)
      r.fail(ptr + "/" + k, "terrain type '" + spec.type + "' does not use '" + k + "' (" + reason(k) + ")");
  }
}

// Every field of the type, with its range; a file must exist.
static void parseTerrainFields(const ConfigReader& r, const json& t, const std::string& ptr, const std::string& base,
                               TerrainSpec& spec) {
  const bool gdal = spec.type == "gdal", raw = isRawTerrain(spec), procedural = isProceduralTerrain(spec);
  if (!procedural) {
    if (!t.contains("file")) r.fail(ptr, "terrain type '" + spec.type + "' needs a 'file'");
    spec.file = inputFile(r, t["file"], ptr + "/file", base, "heightmap file");
    spec.heightScale = 1.0f;
  }
  if (spec.type == "voids") spec.heightScale = 1.0f;  // an SRTM tile: metres, like hgt files
  if (gdal) spec.extent = 0.0f;                       // from the file's georeferencing unless "extent" is given
  // One image stops at 32768, the largest maxImageDimension2D of current GPUs (an H100 takes 32759^2);
  // a paged terrain ("page") goes past it: the device check before any case says what fits.
  if (t.contains("size")) spec.size = r.integer(t["size"], ptr + "/size", 2, t.contains("page") ? 262145 : 32768);
  if (t.contains("detail")) {  // procedural and canyon: "fixed" (8 octaves, the default) or "resolution"
    if (spec.type != "procedural" && spec.type != "canyon")
      r.fail(ptr + "/detail", "only procedural and canyon terrains take a 'detail'");
    const std::string d = r.string(t["detail"], ptr + "/detail");
    if (d != "fixed" && d != "resolution")
      r.fail(ptr + "/detail", "'" + printable(d) + "' is not one of fixed, resolution");
    spec.detailToSpacing = d == "resolution";
  }
  if (t.contains("extent")) spec.extent = float(r.number(t["extent"], ptr + "/extent", 1e-3, 1e9));
  // Procedural heights span [0, height_scale], so its bound is the height bound (kMaxAbsHeight);
  // for files the product with the stored values is checked when the file is read below.
  if (t.contains("height_scale"))
    spec.heightScale = float(r.number(t["height_scale"], ptr + "/height_scale", 0, procedural ? kMaxAbsHeight : 1e9));
  if (t.contains("width")) spec.rawWidth = r.integer(t["width"], ptr + "/width", 2, 65536);
  if (t.contains("height")) spec.rawHeight = r.integer(t["height"], ptr + "/height", 2, 65536);
  if (t.contains("origin")) {  // [x, z]: world position of the terrain's corner (scenario "far from the origin")
    if (!t["origin"].is_array() || t["origin"].size() != 2) r.fail(ptr + "/origin", "expected [x, z]");
    spec.originX = r.number(t["origin"][0], ptr + "/origin/0", -1e8, 1e8);
    spec.originZ = r.number(t["origin"][1], ptr + "/origin/1", -1e8, 1e8);
  }
  if (raw && (spec.rawWidth == 0 || spec.rawHeight == 0)) r.fail(ptr, "raw terrain needs 'width' and 'height'");
  if (t.contains("band")) spec.band = r.integer(t["band"], ptr + "/band", 1, 65535);
  if (t.contains("overview")) spec.overview = r.integer(t["overview"], ptr + "/overview", 1, 30);
  // Cells a device page holds a side (docs/tiled-heightfield.md); absent: one page, the single image.
  if (t.contains("page")) spec.page = r.integer(t["page"], ptr + "/page", 1, 65536);
  if (t.contains("window")) {  // [x, y, w, h] in the raster's pixels; checked against its size when read
    const json& w = t["window"];
    if (!w.is_array() || w.size() != 4) r.fail(ptr + "/window", "expected [x, y, width, height] in pixels");
    for (size_t i = 0; i < 4; ++i)
      spec.window.push_back(r.integer(w[i], ptr + "/window/" + std::to_string(i), i < 2 ? 0 : 2, 2147483647));
  }
}

// One spec per seed where "seed" is a list.
static std::vector<TerrainSpec> terrainSeeds(const ConfigReader& r, const json& t, const std::string& ptr,
                                             TerrainSpec spec) {
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

static std::vector<TerrainSpec> parseTerrain(const ConfigReader& r, const json& t, const std::string& ptr,
                                             const std::string& base) {
  r.onlyKeys(t, ptr,
             {"type", "file", "size", "seed", "extent", "height_scale", "width", "height", "origin", "band", "window",
              "overview", "detail", "page"});
  TerrainSpec spec;
  parseTerrainType(r, t, ptr, spec);
  parseTerrainFields(r, t, ptr, base, spec);
  // Read the file now, so a bad heightmap stops the run before any case instead of failing each one.
  if (!isProceduralTerrain(spec)) {
    try {
      sharedHeightfield(spec);  // kept when large: the cases take it from there instead of reading it again
    } catch (const InputError& e) {
      r.fail(ptr + "/file", e.what());
    }
  }
  return terrainSeeds(r, t, ptr, spec);
}

void parseTerrainSection(const ConfigReader& r, const json& j, const std::string& baseDir, Config& c) {
  auto add = [&](const json& t, const std::string& ptr) {
    const std::vector<TerrainSpec> specs = parseTerrain(r, t, ptr, baseDir);
    const bool seeds = t.contains("seed") && t["seed"].is_array();  // one spec per listed seed
    for (size_t i = 0; i < specs.size(); ++i) {
      c.terrains.push_back(specs[i]);
      c.terrainFields.push_back(seeds ? ptr + "/seed/" + std::to_string(i) : ptr);
    }
  };
  if (j.contains("terrain")) add(j["terrain"], "/terrain");
  if (j.contains("terrains")) {
    // An empty list would silently run the one "terrain" (or the default) alone: say so instead.
    if (!j["terrains"].is_array() || j["terrains"].empty())
      r.fail("/terrains", "expected a non-empty array of terrains (or leave 'terrains' out)");
    for (size_t i = 0; i < j["terrains"].size(); ++i) add(j["terrains"][i], "/terrains/" + std::to_string(i));
  }
  if (c.terrains.empty()) {
    c.terrains.push_back(TerrainSpec{});
    c.terrainFields.push_back("/terrain");
  }
}

// Parameters named <x>min / <x>max bound a range whose width divides (distance falloff): an empty
// range is rejected for every scheme alike, so one scheme cannot accept what another refuses.
static void requireRanges(const ConfigReader& r, const SchemeInfo& info, const ParamValues& pv,
                          const std::string& ptr) {
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

// "tune": {"grid": [16, 64, 256], "subd": [2, 3]}: settings a tuned matched search tries, each a
// list of values in its range; the main parameter is the one the search itself finds.
static void parseTune(const ConfigReader& r, const Scheme& scheme, const json& t, const std::string& ptr,
                      SchemeEntry& e) {
  if (!t.is_object()) r.fail(ptr, "expected an object of setting: [values] (\"grid\" or a parameter)");
  const SchemeInfo& info = scheme.info();
  for (auto& [k, v] : t.items()) {
    const std::string at = ptr + "/" + k;
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& p : info.params)
      if (p.name == k) spec = &p;
    if (k == info.mainParam)
      r.fail(at, "'" + k + "' is " + info.name + "'s main parameter: the matched search finds it");
    if (k != "grid" && !spec) {
      std::vector<std::string> names{"grid"};
      for (const ParamSpec& p : info.params)
        if (p.name != info.mainParam) names.push_back(p.name);
      r.fail(at, "'" + printable(k) + "' is neither grid nor a parameter of " + info.name + didYouMean(k, names));
    }
    if (k == "grid" && !drawsPatchGrid(info)) r.fail(at, info.name + " draws no patch grid: grid does not change it");
    if (!v.is_array() || v.empty()) r.fail(at, "expected a non-empty list of values");
    std::vector<double> values;
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string vi = at + "/" + std::to_string(i);
      values.push_back(k == "grid" ? double(r.integer(v[i], vi, 1, 1024)) : r.number(v[i], vi, spec->min, spec->max));
      if (spec && spec->integer && values.back() != std::round(values.back())) r.fail(vi, "expected an integer");
      if (std::count(values.begin(), values.end(), values.back()) > 1) r.fail(vi, "value listed twice; remove one");
    }
    e.tune[k] = values;
  }
  e.tuneGiven = true;
}

static bool isFront(const ConfigReader& r, const json& s, const std::string& ptr) {
  if (!s.is_object() || !s.contains("front")) return false;
  if (!s["front"].is_boolean()) r.fail(ptr + "/front", "expected true or false");
  return s["front"].get<bool>();
}

static SchemeEntry parseScheme(const ConfigReader& r, const json& s, const std::string& ptr) {
  SchemeEntry e;
  e.field = ptr;
  json params = json::object();
  if (s.is_string()) {
    e.name = s.get<std::string>();
  } else {
    r.onlyKeys(s, ptr, {"name", "params", "tune", "front"});
    if (!s.contains("name")) r.fail(ptr, "missing 'name'");
    e.name = r.string(s["name"], ptr + "/name");
    if (s.contains("params")) params = s["params"];
  }
  const Scheme* scheme = findScheme(e.name);
  if (!scheme) r.fail(ptr + (s.is_string() ? "" : "/name"), unknownSchemeText(printable(e.name)));
  // "front": true sweeps the main parameter over the values the scheme names (SchemeInfo::front).
  if (isFront(r, s, ptr)) {
    const SchemeInfo& info = scheme->info();
    if (info.front.empty()) r.fail(ptr + "/front", info.name + " has no main parameter to sweep");
    if (params.is_object() && params.contains(info.mainParam))
      r.fail(ptr + "/params/" + info.mainParam, "'front' sweeps " + info.mainParam + " already; list one or the other");
    if (params.is_object()) params[info.mainParam] = info.front;
  }
  if (s.is_object() && s.contains("tune")) parseTune(r, *scheme, s["tune"], ptr + "/tune", e);
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

static bool isGroupName(const std::string& name) {
  const std::vector<std::string>& groups = schemeGroupNames();
  return std::find(groups.begin(), groups.end(), name) != groups.end();
}

// A group entry, "all" or {"group": "all", "except": ["reference"], "front": true}: each scheme of
// the group that no entry names and no earlier group took, at its defaults or over its front.
static std::vector<SchemeEntry> parseGroup(const ConfigReader& r, const json& s, const std::string& ptr,
                                           const std::set<std::string>& named, std::set<std::string>& taken) {
  std::string group = s.is_string() ? s.get<std::string>() : "";
  std::set<std::string> except;
  if (s.is_object()) {
    r.onlyKeys(s, ptr, {"group", "except", "front"});
    group = r.string(s["group"], ptr + "/group");
  }
  std::string groups;
  for (const std::string& g : schemeGroupNames()) groups += (groups.empty() ? "" : ", ") + g;
  if (!isGroupName(group))
    r.fail(ptr + "/group", "'" + printable(group) + "' is no scheme group (groups: " + groups + ")" +
                               didYouMean(group, schemeGroupNames()));
  std::vector<std::string> members;
  for (const Scheme* m : schemeGroup(group)) members.push_back(m->info().name);
  if (s.is_object() && s.contains("except")) {
    const json& x = s["except"];
    if (!x.is_array()) r.fail(ptr + "/except", "expected an array of scheme names");
    for (size_t i = 0; i < x.size(); ++i) {
      const std::string at = ptr + "/except/" + std::to_string(i), name = r.string(x[i], at);
      if (std::find(members.begin(), members.end(), name) == members.end())
        r.fail(at, "'" + printable(name) + "' is not in group '" + group + "'" + didYouMean(name, members));
      except.insert(name);
    }
  }
  const bool front = isFront(r, s, ptr);
  std::vector<SchemeEntry> out;
  for (const Scheme* m : schemeGroup(group)) {
    const SchemeInfo& info = m->info();
    if (named.count(info.name) || except.count(info.name) || !taken.insert(info.name).second) continue;
    json entry = {{"name", info.name}};
    if (front && !info.front.empty()) entry["front"] = true;  // a scheme without a main parameter runs once
    out.push_back(parseScheme(r, entry, ptr));
  }
  if (out.empty()) r.fail(ptr, "group '" + group + "' adds no scheme: another entry names or excepts each of them");
  return out;
}

void parseSchemeSection(const ConfigReader& r, const json& j, Config& c) {
  if (!j.contains("schemes") || !j["schemes"].is_array() || j["schemes"].empty())
    r.fail("/schemes", "expected a non-empty array of schemes or groups (\"all\"; known: " + schemeNames() + ")");
  const json& list = j["schemes"];
  auto groupEntry = [](const json& s) {
    return s.is_string() ? isGroupName(s.get<std::string>()) : s.contains("group");
  };
  std::set<std::string> named, taken;
  for (const json& s : list)
    if (!groupEntry(s)) {
      if (s.is_string()) named.insert(s.get<std::string>());
      if (s.is_object() && s.contains("name") && s["name"].is_string()) named.insert(s["name"].get<std::string>());
    }
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string ptr = "/schemes/" + std::to_string(i);
    if (list[i].is_object() && list[i].contains("group") && list[i].contains("name"))
      r.fail(ptr, "an entry names a scheme ('name') or a group ('group'), not both");
    if (!groupEntry(list[i])) {
      c.schemes.push_back(parseScheme(r, list[i], ptr));
      continue;
    }
    for (SchemeEntry& e : parseGroup(r, list[i], ptr, named, taken)) c.schemes.push_back(std::move(e));
  }
}

// "plugins": ["build/libmyscheme.so"]: scheme libraries (schemes/plugins.h), relative to the
// config's folder, loaded before the schemes are read so that entries and groups take their schemes.
static void parsePluginSection(const ConfigReader& r, const json& j, const std::string& baseDir, Config& c) {
  if (!j.contains("plugins")) return;
  if (!j["plugins"].is_array()) r.fail("/plugins", "expected an array of plugin library files");
  for (size_t i = 0; i < j["plugins"].size(); ++i) {
    const std::string ptr = "/plugins/" + std::to_string(i);
    const std::string file = resolvePath(baseDir, r.string(j["plugins"][i], ptr));
    try {
      loadPlugin(file);
    } catch (const InputError& e) {
      r.fail(ptr, e.what());
    }
    c.plugins.push_back(file);
  }
}

Config parseConfig(const std::string& text, const std::string& file, const std::string& baseDir) {
  json j = parseJsonStrict(text, file);
  ConfigReader r{file, jsonLineMap(text)};
  r.onlyKeys(j, "", {"name",          "device",     "resolution",  "resolutions",    "grid",    "grids",       "fps",
                     "warmup_frames", "max_frames", "repetitions", "case_timeout_s", "terrain", "terrains",    "path",
                     "paths",         "schemes",    "images",      "measure",        "match",   "description", "timing",
                     "calibration",   "energy",     "interleave",  "plugins"});
  Config c;
  c.file = file;
  c.lines = r.lines;
  c.raw = j;
  parseNameSection(r, j, c);
  parseResolutionSection(r, j, c);
  parseGridSection(r, j, c);
  parseFrameSection(r, j, c);
  parseTerrainSection(r, j, baseDir, c);
  const std::vector<int> pathFrames = parsePathSection(r, j, baseDir, c);
  parsePluginSection(r, j, baseDir, c);
  parseSchemeSection(r, j, c);
  parseImageSection(r, j, pathFrames, c);
  parseTimingSection(r, j, c);
  parseCalibrationSection(r, j, c);
  parseEnergySection(r, j, c);
  parseMeasureSection(r, j, c);
  parseMatchSection(r, j, c);
  for (const SchemeEntry& e : c.schemes)
    if (e.tuneGiven && !c.match.on()) r.fail(e.field + "/tune", "tuning needs a \"match\" section (a target to reach)");
  return c;
}

Config loadConfig(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError("config '" + file + "' is a directory, not a JSON file");
  std::ifstream f(file);
  if (!f) throw InputError("cannot open config '" + file + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  auto slash = file.find_last_of('/');
  return parseConfig(ss.str(), file, slash == std::string::npos ? "." : file.substr(0, slash));
}

std::string terrainLabel(const TerrainSpec& t) {
  if (t.page > 0) {  // the same heights in pages: a case of its own beside the single image's
    TerrainSpec single = t;
    single.page = 0;
    return terrainLabel(single) + "-p" + std::to_string(t.page);
  }
  if (t.originX != 0 || t.originZ != 0) {
    TerrainSpec atOrigin = t;
    atOrigin.originX = atOrigin.originZ = 0;
    // Whole metres keep the label free of exponents ("1e+07").
    return terrainLabel(atOrigin) + "-at" + std::to_string(std::llround(t.originX)) + "_" +
           std::to_string(std::llround(t.originZ));
  }
  if (t.type == "procedural")
    return "proc" + std::to_string(t.size) + "s" + std::to_string(t.seed) + (t.detailToSpacing ? "-detail" : "");
  if (t.type == "voids") return "voids1201s" + std::to_string(t.seed);  // the tile's size, not t.size
  if (isGeneratedTerrain(t.type))
    return t.type + std::to_string(t.size) + "s" + std::to_string(t.seed) + (t.detailToSpacing ? "-detail" : "");
  auto slash = t.file.find_last_of('/');
  std::string stem = t.file.substr(slash == std::string::npos ? 0 : slash + 1);
  stem = stem.substr(0, stem.find('.'));
  // Two bands, windows or overviews of one file are different terrains: say so in the label.
  if (t.band > 0) stem += "-b" + std::to_string(t.band);
  if (t.window.size() == 4)
    stem += "-w" + std::to_string(t.window[0]) + "_" + std::to_string(t.window[1]) + "_" + std::to_string(t.window[2]) +
            "x" + std::to_string(t.window[3]);
  if (t.overview > 0) stem += "-o" + std::to_string(t.overview);
  return stem;
}

static std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

static std::string paramsText(const ParamValues& params) {
  std::string s;
  for (auto& [k, v] : params) s += (s.empty() ? "" : " ") + k + "=" + formatNumber(v);
  return s.empty() ? "(defaults)" : s;
}

static std::string fileStem(const std::string& path) {
  auto slash = path.find_last_of('/');
  std::string stem = path.substr(slash == std::string::npos ? 0 : slash + 1);
  return stem.substr(0, stem.find('.'));
}

std::string configField(const Config& config, const std::string& ptr) {
  auto it = config.lines.find(ptr);
  return config.file + (it != config.lines.end() ? ":" + std::to_string(it->second) : "") + ": field '" +
         (ptr.empty() ? "/" : ptr) + "'";
}

// ", line 7" for the entry at ptr where its line is known, else "".
static std::string lineOf(const Config& config, const std::string& ptr) {
  auto it = config.lines.find(ptr);
  return it != config.lines.end() ? ", line " + std::to_string(it->second) : "";
}

// Entry i and j of one config list are the same: an error naming both, at the second one's line
// (a sweep that ran them would run one case twice under one id, or silently keep one). field(i)
// is entry i's JSON pointer, "" where unknown (a Config built in code).
template <typename T, typename Same, typename Name, typename Field>
static void rejectDuplicates(const Config& config, const std::vector<T>& items, const char* what, Same same, Name name,
                             Field field) {
  for (size_t i = 0; i < items.size(); ++i)
    for (size_t j = i + 1; j < items.size(); ++j)
      if (same(items[i], items[j])) {
        const std::string fi = field(i), fj = field(j);
        const std::string entry = std::string(what) + " #" + std::to_string(i + 1) + " (" + name(items[i]) +
                                  (fi.empty() ? "" : "; " + fi + lineOf(config, fi)) + ") and #" +
                                  std::to_string(j + 1) + " (" + name(items[j]) + ") are the same; remove one";
        throw InputError(fj.empty() ? config.file + ": " + entry : configField(config, fj) + ": " + entry);
      }
}

std::vector<Case> expandCases(const Config& config) {
  FileDigests files;
  std::vector<nlohmann::json> terrains, paths;
  std::vector<std::string> labels;
  for (auto& t : config.terrains) {
    terrains.push_back(terrainInputs(t, files));
    labels.push_back(terrainLabel(t));
  }
  for (auto& p : config.paths) paths.push_back(pathInputs(p, files));
  std::vector<size_t> tIdx(terrains.size()), pIdx(paths.size());
  for (size_t i = 0; i < tIdx.size(); ++i) tIdx[i] = i;
  for (size_t i = 0; i < pIdx.size(); ++i) pIdx[i] = i;
  auto fieldOf = [](const std::vector<std::string>& fields) {
    return [&fields](size_t i) { return i < fields.size() ? fields[i] : std::string(); };
  };
  rejectDuplicates(
      config, tIdx, "terrain", [&](size_t a, size_t b) { return terrains[a] == terrains[b]; },
      [&](size_t a) { return labels[a]; }, fieldOf(config.terrainFields));
  rejectDuplicates(
      config, pIdx, "camera path", [&](size_t a, size_t b) { return paths[a] == paths[b]; },
      [&](size_t a) { return config.paths[a]; }, fieldOf(config.pathFields));
  // Either key takes a list of pairs; "resolutions" wins where both are given (parseResolutionSection).
  const std::string resField = config.lines.count("/resolutions")  ? "/resolutions/"
                               : config.lines.count("/resolution") ? "/resolution/"
                                                                   : "";
  rejectDuplicates(
      config, config.resolutions, "resolution", [](auto& a, auto& b) { return a == b; },
      [](auto& r) { return std::to_string(r.first) + "x" + std::to_string(r.second); },
      [&](size_t i) { return resField.empty() ? resField : resField + std::to_string(i); });
  struct Variant {
    std::string scheme;
    ParamValues params;
    size_t entry;
  };
  std::vector<Variant> variants;
  for (size_t i = 0; i < config.schemes.size(); ++i)
    for (auto& v : config.schemes[i].variants) variants.push_back({config.schemes[i].name, v, i});
  // A parameter given at its default value is the same case as one left out.
  auto resolved = [](const Variant& v) { return resolveParams(findScheme(v.scheme)->info(), v.params); };
  for (size_t i = 0; i < variants.size(); ++i)
    for (size_t j = i + 1; j < variants.size(); ++j)
      if (variants[i].scheme == variants[j].scheme && resolved(variants[i]) == resolved(variants[j]) &&
          config.schemes[variants[i].entry].tune == config.schemes[variants[j].entry].tune) {
        // At the second entry's line, naming the first's: "c.json:9: field '/schemes/2': /schemes/0
        // (line 7) and /schemes/2 both run uniform level=3; remove one".
        const std::string first = config.schemes[variants[i].entry].field,
                          second = config.schemes[variants[j].entry].field;
        const std::string firstLine = lineOf(config, first);
        std::string what = first == second ? first + " lists twice: " + variants[i].scheme + " "
                                           : first + (firstLine.empty() ? "" : " (" + firstLine.substr(2) + ")") +
                                                 " and " + second + " both run " + variants[i].scheme + " ";
        what += paramsText(variants[i].params);
        if (variants[i].params != variants[j].params)  // one lists a default the other leaves out
          what += " (also listed as " + paramsText(variants[j].params) + ")";
        throw InputError(configField(config, second) + ": " + what + "; remove one");
      }
  // Terrains that differ only in what the label leaves out (extent, height scale, file type...)
  // keep readable, distinct labels.
  for (size_t i = 0; i < labels.size(); ++i)
    if (std::count(labels.begin(), labels.end(), labels[i]) > 1)
      labels[i] += "-" + inputsDigest(terrains[i]).substr(0, 6);

  std::vector<Case> cases;
  for (int grid : config.grids) {
    nlohmann::json measurement = measurementInputs(config);
    measurement["grid"] = grid;
    for (size_t ti = 0; ti < config.terrains.size(); ++ti)
      for (size_t pi = 0; pi < config.paths.size(); ++pi)
        for (auto& res : config.resolutions)
          for (auto& v : variants) {
            const TerrainSpec& t = config.terrains[ti];
            const std::string& path = config.paths[pi];
            Case c{"", v.scheme, v.params, v.params, t, labels[ti], path, res.first, res.second};
            c.id = v.scheme;
            for (auto& [k, val] : v.params) c.id += "-" + k + formatNumber(val);
            c.id += "_" + c.terrainLabel + "_" + fileStem(path) + "_" + std::to_string(res.first) + "x" +
                    std::to_string(res.second);
            if (config.grids.size() > 1) c.id += "_g" + std::to_string(grid);
            c.grid = grid;
            if (config.match.on()) c.id += "_match-" + config.match.metric + formatNumber(config.match.value);
            const SchemeEntry& entry = config.schemes[v.entry];
            if (config.match.on())
              c.tune = entry.tuneGiven     ? entry.tune
                       : config.match.tune ? defaultTuneSpace(*findScheme(v.scheme))
                                           : TuneSpace{};
            if (!c.tune.empty()) c.id += "_tuned";
            // Every parameter with its resolved value: a default that changes meaning changes the digest.
            c.params = resolved(v);
            nlohmann::json params = nlohmann::json::object();
            for (auto& [k, val] : c.params) params[k] = val;
            c.inputs = caseInputs(terrains[ti], paths[pi], res.first, res.second, v.scheme, params, measurement);
            if (!c.tune.empty()) c.inputs["tune"] = c.tune;  // named only when tuned: earlier digests hold
            c.digest = inputsDigest(c.inputs);
            c.terrainDigest = inputsDigest(terrains[ti]);
            cases.push_back(std::move(c));
          }
  }
  // Readable parts that still coincide (paths with one stem in two folders, parameter values equal
  // to 6 digits): a digest suffix on each.
  std::map<std::string, int> count;
  for (auto& c : cases) count[c.id]++;
  for (auto& c : cases)
    if (count[c.id] > 1) c.id += "_" + c.digest.substr(0, 8);
  std::map<std::string, const Case*> seen;
  for (auto& c : cases)
    if (!seen.emplace(c.id, &c).second)  // equal digests: every duplicate list is rejected above
      throw InputError(config.file + ": two cases with the same inputs: " + c.id);
  return cases;
}

}  // namespace lb
