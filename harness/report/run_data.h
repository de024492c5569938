#pragma once
// A finished (or interrupted) run directory read back for the report: run.json, summary.json and
// cases/*.json (docs/results-format.md) through results/run_dir.h and results/run_read.h. A
// missing summary.json or metric is not an error (the report says what it could not show); an
// unreadable case file is.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "results/run_read.h"

namespace lb {

// A case as the report shows it: its record (results/run_read.h) and the labels it goes by.
struct ReportCase : CaseRecord {
  std::string paramsLabel;  // "tri_size=2, alpha=0.75", or "defaults"
  std::string label;        // scheme + parameters, for legends
  std::string scenario;     // camera path stem (+ terrain, resolution where the run varies them)
};

// Images of one case: frame -> mode -> path relative to the run directory.
using CaseImages = std::map<int, std::map<std::string, std::string>>;

struct ReportRun {
  std::string dir;
  std::string name;  // config name, or the directory name
  nlohmann::json run = nlohmann::json::object();
  nlohmann::json context = nlohmann::json::object();
  std::vector<ReportCase> cases;             // config order: scheme, path, then parameter values
  std::map<std::string, CaseImages> images;  // by case id, from images/<case>_f<frame>_<mode>.png
  std::vector<std::string> schemes;          // in order of first appearance (fixes chart colours)
  std::vector<std::string> scenarios;
  std::vector<std::string> paramLabels;  // parameter labels of finished cases, natural order
  std::vector<std::string> notes;        // files that were missing or unreadable
};

// Throws InputError when dir is not a run directory (neither summary.json nor cases/).
ReportRun loadReportRun(const std::string& dir);

// summary[key][stat] as a number; nullopt when the metric is absent or null.
std::optional<double> summaryStat(const nlohmann::json& summary, const std::string& key, const std::string& stat);
// A number from a per-frame record; nullopt when absent or null.
std::optional<double> frameValue(const nlohmann::json& frame, const std::string& key);

// Three significant digits, no exponent for ordinary magnitudes, integers as integers.
std::string formatValue(double v);
std::string formatValue(const std::optional<double>& v);  // "–" when missing

}  // namespace lb
