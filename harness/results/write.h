#pragma once
// Result files (docs/design.md, Output): run.json, cases/<id>.json, frames.csv, summary.json.
// Every write is atomic (temp file + rename), so a killed run leaves no corrupt file.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics/frame_metrics.h"
#include "render/frame_data.h"
#include "render/scheme.h"
#include "terrain/heightfield.h"

namespace lb {

constexpr int kSchemaVersion = 1;

struct Context;
struct Config;
struct Case;

struct CaseResult {
  std::string status = "ok";  // ok | failed | skipped
  std::string reason;
  std::vector<FrameResult> frames;
  std::vector<FrameMetrics> metrics;  // measurement frames (images dropped after use)
  double targetAreaPx = 0;            // the scheme's target triangle area, 0 = none
  nlohmann::json matched;             // matched-comparison search result (null when off)
  int grid = 0;                       // the patch grid the case drew (a tuned search's choice); 0: the case's own
  ParamValues params;                 // the parameters the case drew (after a matched or tuned search)
  std::vector<std::string> images;    // relative to the run dir
  double seconds = 0;
  // Timing modes other than shaded: mode -> frames in the order of `frames`.
  std::map<std::string, std::vector<FrameResult>> modeFrames;
  nlohmann::json calibration;   // clock-control calibration (null when off)
  TerrainSource terrainSource;  // what the case's terrain was read from (driver "": generated or never read)
  // Samples of the terrain the case ran on (after a gdal window and overview); 0 = never loaded.
  int terrainWidth = 0, terrainHeight = 0;
  // Stateful GPU LOD (replay/lod_replay.h): converge_updates, lod_converged and the state's size
  // facts, merged into the case summary; null for every other scheme.
  nlohmann::json lodState;
  // Energy per frame (replay/energy_pass.h energyJson): {"energy_j_per_frame", "energy_reason"},
  // merged into the case summary; null where the case never reached the pass.
  nlohmann::json energy;
  // How long the LOD lags the camera (replay/settle.h settleJson), the summary's "settle"; null where
  // the error pass did not run.
  nlohmann::json settle;
  // Device memory of the case's renderer by resource and the host's peak (results/memory_json.h),
  // the summary's "memory"; null where the case never reached its end.
  nlohmann::json memory;
};

void writeFileAtomic(const std::string& path, const std::string& contents);
std::string gitCommit();
std::string isoTimeUtc();
// The context block every result file carries (tool, commit, device, driver, host, time, config).
nlohmann::json runContext(const Context& ctx, const Config& config);
nlohmann::json caseSummary(const CaseResult& r);
nlohmann::json caseJson(const Case& c, const CaseResult& r);
// Wall ms per measured frame, in all and per measurement pass (FrameMetrics::costs); null without
// measured frames. Case records' measure_costs_ms; run.json's sums them over the invocation.
nlohmann::json measureCostsJson(const std::vector<FrameMetrics>& metrics);
// frames.csv: case_id, the timing and metric columns, then scheme and one param_<name> column per
// parameter any case of the run has (sorted; empty where a case's scheme has no such parameter).
std::string framesCsvHeader(const std::vector<std::string>& params);
// One CSV row per frame record of a case file (metric columns empty on unmeasured frames).
std::string framesCsvRows(const nlohmann::json& caseFile, const std::vector<std::string>& params);

}  // namespace lb
