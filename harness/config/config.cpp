#include "config/config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <fstream>
#include <set>
#include <sstream>

#include "config/case_identity.h"
#include "config/config_sections.h"
#include "config/json_lines.h"
#include "config/json_strict.h"
#include "error.h"
#include "terrain/generators.h"

namespace lb {

using nlohmann::json;

Config parseConfig(const std::string& text, const std::string& file, const std::string& baseDir) {
  json j = parseJsonStrict(text, file);
  ConfigReader r{file, jsonLineMap(text)};
  r.onlyKeys(j, "", {"name", "device", "resolution", "resolutions", "grid", "grids", "fps", "warmup_frames", "max_frames",
                     "repetitions", "case_timeout_s", "terrain", "terrains", "path", "paths", "schemes", "images", "measure", "match",
                     "description", "timing", "calibration"});
  Config c;
  c.file = file;
  c.raw = j;
  parseNameSection(r, j, c);
  parseResolutionSection(r, j, c);
  parseGridSection(r, j, c);
  parseFrameSection(r, j, c);
  parseTerrainSection(r, j, baseDir, c);
  const std::vector<int> pathFrames = parsePathSection(r, j, baseDir, c);
  parseSchemeSection(r, j, c);
  parseImageSection(r, j, pathFrames, c);
  parseTimingSection(r, j, c);
  parseCalibrationSection(r, j, c);
  parseMeasureSection(r, j, c);
  parseMatchSection(r, j, c);
  return c;
}

Config loadConfig(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw InputError("config '" + file + "' is a directory, not a JSON file");
  std::ifstream f(file);
  if (!f) throw InputError("cannot open config '" + file + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  auto slash = file.find_last_of('/');
  return parseConfig(ss.str(), file, slash == std::string::npos ? "." : file.substr(0, slash));
}

std::string terrainLabel(const TerrainSpec& t) {
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
  if (isGeneratedTerrain(t.type)) return t.type + std::to_string(t.size) + "s" + std::to_string(t.seed);
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

// Entry i and j of one config list are the same: an error naming both (a sweep that ran them
// would run one case twice under one id, or silently keep one).
template <typename T, typename Same, typename Name>
static void rejectDuplicates(const Config& config, const std::vector<T>& items, const char* what, Same same,
                             Name name) {
  for (size_t i = 0; i < items.size(); ++i)
    for (size_t j = i + 1; j < items.size(); ++j)
      if (same(items[i], items[j]))
        throw InputError(config.file + ": " + what + " #" + std::to_string(i + 1) + " (" + name(items[i]) + ") and #" +
                         std::to_string(j + 1) + " (" + name(items[j]) + ") are the same; remove one");
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
  rejectDuplicates(config, tIdx, "terrain", [&](size_t a, size_t b) { return terrains[a] == terrains[b]; },
                   [&](size_t a) { return labels[a]; });
  rejectDuplicates(config, pIdx, "camera path", [&](size_t a, size_t b) { return paths[a] == paths[b]; },
                   [&](size_t a) { return config.paths[a]; });
  rejectDuplicates(config, config.resolutions, "resolution", [](auto& a, auto& b) { return a == b; },
                   [](auto& r) { return std::to_string(r.first) + "x" + std::to_string(r.second); });
  struct Variant {
    std::string scheme;
    ParamValues params;
    size_t entry;
  };
  std::vector<Variant> variants;
  for (size_t i = 0; i < config.schemes.size(); ++i)
    for (auto& v : config.schemes[i].variants) variants.push_back({config.schemes[i].name, v, i});
  for (size_t i = 0; i < variants.size(); ++i)
    for (size_t j = i + 1; j < variants.size(); ++j)
      if (variants[i].scheme == variants[j].scheme && variants[i].params == variants[j].params)
        throw InputError(config.file + ": /schemes/" + std::to_string(variants[i].entry) + " and /schemes/" +
                         std::to_string(variants[j].entry) + " both run " + variants[i].scheme + " " +
                         paramsText(variants[i].params) + "; remove one");
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
          Case c{"", v.scheme, v.params, t, labels[ti], path, res.first, res.second};
          c.id = v.scheme;
          for (auto& [k, val] : v.params) c.id += "-" + k + formatNumber(val);
          c.id += "_" + c.terrainLabel + "_" + fileStem(path) + "_" + std::to_string(res.first) + "x" +
                  std::to_string(res.second);
          if (config.grids.size() > 1) c.id += "_g" + std::to_string(grid);
          c.grid = grid;
          if (config.match.on()) c.id += "_match-" + config.match.metric + formatNumber(config.match.value);
          nlohmann::json params = nlohmann::json::object();
          for (auto& [k, val] : v.params) params[k] = val;
          c.inputs = caseInputs(terrains[ti], paths[pi], res.first, res.second, v.scheme, params, measurement);
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
