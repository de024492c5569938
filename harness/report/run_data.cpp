#include "report/run_data.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>

#include "error.h"
#include "results/run_dir.h"
#include "results/run_read.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

static std::optional<json> readJson(const fs::path& file, std::vector<std::string>& notes) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    notes.push_back(file.string() + ": unreadable JSON (" + e.what() + ")");
    return std::nullopt;
  }
}

static std::string str(const json& j, const char* key) {
  auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

static std::string paramsLabel(const json& params) {
  std::string s;
  for (auto& [k, v] : params.items()) {
    if (!s.empty()) s += ", ";
    s += k + "=" + (v.is_number() ? formatValue(v.get<double>()) : v.dump());
  }
  return s.empty() ? "defaults" : s;
}

static void scanImages(ReportRun& run) {
  fs::path dir = fs::path(run.dir) / "images";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::set<std::string> ids;
  for (auto& c : run.cases) ids.insert(c.id);
  for (auto& entry : fs::directory_iterator(dir, ec)) {
    std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".png") continue;
    // <case-id>_f<frame>_<mode>.png; the case id itself may contain "_f" (e.g. "_flyover").
    std::string stem = entry.path().stem().string();
    size_t modeAt = stem.rfind('_');
    if (modeAt == std::string::npos) continue;
    size_t frameAt = stem.rfind("_f", modeAt - 1);
    if (frameAt == std::string::npos) continue;
    std::string id = stem.substr(0, frameAt), digits = stem.substr(frameAt + 2, modeAt - frameAt - 2);
    if (!ids.count(id) || digits.empty() || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    run.images[id][std::stoi(digits)][stem.substr(modeAt + 1)] = "images/" + name;
  }
}

// "level=4" before "level=16": digit runs compare as numbers.
static bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit((unsigned char)a[i]) && std::isdigit((unsigned char)b[j])) {
      size_t i2 = i, j2 = j;
      while (i2 < a.size() && (std::isdigit((unsigned char)a[i2]) || a[i2] == '.')) ++i2;
      while (j2 < b.size() && (std::isdigit((unsigned char)b[j2]) || b[j2] == '.')) ++j2;
      double x = std::atof(a.substr(i, i2 - i).c_str()), y = std::atof(b.substr(j, j2 - j).c_str());
      if (x != y) return x < y;
      i = i2;
      j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// Position of name in the config's list (schemes by name, paths by stem); unlisted names last.
static size_t configIndex(const json& list, const std::string& name, bool byStem) {
  if (!list.is_array()) return list.size() + 1;
  for (size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    std::string s = e.is_string() ? e.get<std::string>() : e.is_object() ? str(e, "name") : "";
    if ((byStem ? fs::path(s).stem().string() : s) == name) return i;
  }
  return list.size();
}

// Cases in the config's order: by scheme, path, then parameter values.
static void sortCases(ReportRun& run) {
  json config = run.context.value("config", json::object());
  if (!config.is_object()) config = json::object();
  json schemes = config.value("schemes", json::array()), paths = config.value("paths", json::array());
  auto key = [&](const ReportCase& c) {
    return std::make_tuple(configIndex(schemes, c.scheme, false),
                           configIndex(paths, fs::path(c.path).stem().string(), true), c.scheme, c.scenario);
  };
  std::stable_sort(run.cases.begin(), run.cases.end(), [&](const ReportCase& a, const ReportCase& b) {
    auto ka = key(a), kb = key(b);
    if (ka != kb) return ka < kb;
    return naturalLess(a.paramsLabel, b.paramsLabel);
  });
}

// Scenario = path stem, plus terrain, resolution and grid where the run has more than one of them.
static void labelCases(ReportRun& run) {
  std::set<std::string> terrains, resolutions;
  std::set<int> grids;
  for (auto& c : run.cases) {
    grids.insert(c.grid);
    terrains.insert(c.terrain);
    resolutions.insert(std::to_string(c.width) + "x" + std::to_string(c.height));
  }
  for (auto& c : run.cases) {
    c.paramsLabel = paramsLabel(c.listedParams);  // the values the config lists, not every default
    c.scenario = c.path.empty() ? "(no path)" : fs::path(c.path).stem().string();
    if (terrains.size() > 1) c.scenario += " / " + c.terrain;
    if (resolutions.size() > 1) c.scenario += " / " + std::to_string(c.width) + "x" + std::to_string(c.height);
    if (grids.size() > 1) c.scenario += " / grid " + std::to_string(c.grid);
  }
  sortCases(run);
  for (auto& c : run.cases) {
    c.label = c.scheme + (c.listedParams.empty() ? "" : " " + c.paramsLabel);
    if (c.status == "ok" &&
        std::find(run.paramLabels.begin(), run.paramLabels.end(), c.paramsLabel) == run.paramLabels.end())
      run.paramLabels.push_back(c.paramsLabel);
    if (std::find(run.schemes.begin(), run.schemes.end(), c.scheme) == run.schemes.end())
      run.schemes.push_back(c.scheme);
    if (std::find(run.scenarios.begin(), run.scenarios.end(), c.scenario) == run.scenarios.end())
      run.scenarios.push_back(c.scenario);
  }
  std::sort(run.paramLabels.begin(), run.paramLabels.end(), naturalLess);
}

ReportRun loadReportRun(const std::string& dir) {
  ReportRun run;
  run.dir = dir;
  fs::path root(dir);
  std::error_code ec;
  bool hasSummary = fs::is_regular_file(root / "summary.json", ec), hasCases = fs::is_directory(root / "cases", ec);
  if (!hasSummary && !hasCases)
    throw InputError(dir + ": not a lodbench run directory (no summary.json and no cases/; run `lodbench run` first)");

  if (hasRunJson(dir))
    run.run = readRunJson(dir);  // present but unreadable is an error, as for every reader
  else
    run.notes.push_back("run.json missing: the run's context comes from summary.json");
  std::optional<json> summary = hasSummary ? readJson(root / "summary.json", run.notes) : std::nullopt;
  if (summary && !summary->is_object()) summary.reset();
  if (!summary) run.notes.push_back("summary.json missing (interrupted run?): cases are read from cases/");
  run.context = run.run.value("context", summary ? summary->value("context", json::object()) : json::object());
  if (!run.context.is_object()) run.context = json::object();
  const json config = run.context.value("config", json::object());
  run.name = config.is_object() ? str(config, "name") : "";
  if (run.name.empty()) run.name = fs::absolute(root).lexically_normal().filename().string();

  std::map<std::string, size_t> index;
  if (summary && summary->contains("cases") && (*summary)["cases"].is_array())
    for (auto& j : (*summary)["cases"]) {
      ReportCase c;
      c.id = str(j, "case_id");
      readCaseRecord(c, j);
      index[c.id] = run.cases.size();
      run.cases.push_back(std::move(c));
    }
  // An unreadable case file is an error naming it (results/run_dir.h), never a silently missing case.
  for (auto& cf : readCaseFiles(dir)) {
    std::string id = cf.id();
    if (!index.count(id)) {
      index[id] = run.cases.size();
      run.cases.push_back(ReportCase{});
      run.cases.back().id = id;
    }
    readCaseRecord(run.cases[index[id]], cf.doc);
  }
  for (auto& c : run.cases)
    if (c.status.empty()) c.status = "unknown";
  labelCases(run);
  scanImages(run);
  return run;
}

std::optional<double> summaryStat(const json& summary, const std::string& key, const std::string& stat) {
  auto it = summary.find(key);
  if (it == summary.end() || !it->is_object()) return std::nullopt;
  auto s = it->find(stat);
  if (s == it->end() || !s->is_number()) return std::nullopt;
  return s->get<double>();
}

std::optional<double> frameValue(const json& frame, const std::string& key) {
  auto it = frame.find(key);
  if (it == frame.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

std::string formatValue(double v) {
  char buf[64];
  double a = std::fabs(v);
  if (!std::isfinite(v)) return v != v ? "nan" : v > 0 ? "inf" : "-inf";
  if (a >= 1000 || (a >= 1 && v == std::floor(v)))
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else if (a >= 0.001 || a == 0)
    std::snprintf(buf, sizeof buf, "%.3g", v);
  else
    std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

std::string formatValue(const std::optional<double>& v) {
  return v ? formatValue(*v) : "–";
}

}  // namespace lb
