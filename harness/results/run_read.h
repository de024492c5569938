#pragma once
// The read model of result files that report and compare share: one case as its records say
// (docs/results-format.md). What each command adds (report: labels and images; compare: pooled
// timings of rounds) is a thin view on top, in report/run_data.h and compare/run_data.h. Files
// are read through run_dir.h, so every reader has its error policy.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace lb {

struct CaseRecord {
  std::string id;
  std::string file;                          // cases/<id>.json it came from; "" when only summary.json names the case
  std::string status, reason, scheme, path;  // "" where the record has none
  std::string terrain;                       // the terrain's label
  int width = 0, height = 0;
  int grid = 0;  // patches per side (case file "grid", else inputs.measurement.grid); 0 unknown
  nlohmann::json params = nlohmann::json::object();        // every parameter, resolved
  nlohmann::json listedParams = nlohmann::json::object();  // those the config listed (labels); files
                                                           // without "params_listed": params
  nlohmann::json summary = nlohmann::json::object();
  nlohmann::json frames = nlohmann::json::array();  // per-frame records; empty without a case file
  std::optional<double> targetAreaPx;
  nlohmann::json matched;  // the matched search's result (case file "matched"); null when off
};

// Takes the fields a record has, each only where it has the expected type; fields it lacks keep
// their value. A record is a case file or a summary.json "cases" entry (the case file, read after
// it, wins: it has the terrain object and the frames).
void readCaseRecord(CaseRecord& c, const nlohmann::json& record);

}  // namespace lb
