#pragma once
// A finished run read back from its directory (docs/results-format.md) for lodbench compare and
// A/B mode. Rounds of the same config (A/B mode) pool into one RunData per side.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "results/run_dir.h"
#include "results/run_read.h"

namespace lb {

// A case as compare reads it: its record (results/run_read.h; status "ok" where the case file
// names none) and the GPU times of every round pooled into it.
struct CaseData : CaseRecord {
  std::vector<double> gpuMs;         // every timing frame of every ok round, pooled
  std::vector<double> roundMedians;  // median GPU ms of each round, in run order
  int rounds = 0;                    // ok rounds pooled into gpuMs
};

struct RunData {
  std::string dir;                                    // for one round; "a1, a2, ..." style list when pooled
  nlohmann::json context = nlohmann::json::object();  // run.json "context"
  double testSlowdown = 0;                            // run.json "test_slowdown": a planted slowdown (tests only)
  std::map<std::string, CaseData> cases;              // by case_id
};

// Reads `dir`/run.json and `dir`/cases/*.json. Throws InputError naming the directory or file
// for a missing directory, a missing or unreadable run.json, or a case file that is not JSON or
// lacks case_id / frames.
RunData loadRun(const std::string& dir);
// A run directory, or a folder whose subdirectories are rounds of one config (e.g. a baseline
// recorded as r1/, r2/, r3/): one RunData per round, in numeric name order.
std::vector<RunData> loadRounds(const std::string& dir);
// Pools rounds of one side: context, frames and summaries of the first round; gpu_ms of all
// rounds. A case that failed in any round is failed (its reason names the round).
RunData poolRuns(const std::vector<RunData>& rounds);

}  // namespace lb
