#pragma once
// run.json (docs/results-format.md): what a run is, written before its first case and again
// when it ends; and the run.json of a merged run.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lb {

// At the start: context, start time, shard and case ids. A resumed run (previous = its run.json,
// null when new) keeps its first start time and adds this start to resumed_at.
nlohmann::json startedRunJson(const nlohmann::json& context, int shardIndex, int shardCount,
                              const std::vector<std::string>& caseIds, const nlohmann::json& previous);

// At the end: end time, what the work cost, whether a stop cut it short, and the totals.
struct RunEnd {
  nlohmann::json costs;          // per scheme, and "terrains"
  double rayCastSPerImage = -1;  // < 0: no ray cast was made
  nlohmann::json measureCosts;   // measureCostsJson over this invocation's measured frames
  bool interrupted = false;
  int ok = 0, failed = 0, skipped = 0;
  size_t cases = 0;
  int validationErrors = 0;
};
void endRunJson(nlohmann::json& run, const RunEnd& end);

// A run merged from shards or rounds (sweep/merge.h): the context it keeps, the folders merged,
// the earliest start and latest end among them (null where none has one). No time of the merge
// itself: merging the same folders again gives the same bytes.
nlohmann::json mergedRunJson(const nlohmann::json& context, const nlohmann::json& mergedFrom, bool forced,
                             const nlohmann::json& startTime, const nlohmann::json& endTime);

}  // namespace lb
