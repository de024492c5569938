#include "results/run_json.h"

#include "results/write.h"

namespace lb {

using nlohmann::json;

json startedRunJson(const json& context, int shardIndex, int shardCount, const std::vector<std::string>& caseIds,
                    const json& previous) {
  json ids = json::array();
  for (auto& id : caseIds) ids.push_back(id);
  json run = {{"schema_version", kSchemaVersion},
              {"context", context},
              {"start_time", context["time"]},
              {"shard", {{"index", shardIndex}, {"count", shardCount}}},
              {"case_ids", ids}};
  if (!previous.is_null()) {
    run["start_time"] = previous.value("start_time", context["time"].get<std::string>());
    run["resumed_at"] = previous.value("resumed_at", json::array());
    run["resumed_at"].push_back(context["time"]);
  }
  return run;
}

void endRunJson(json& run, const RunEnd& end) {
  run["end_time"] = isoTimeUtc();
  run["ray_cast_s_per_image"] = end.rayCastSPerImage >= 0 ? json(end.rayCastSPerImage) : json(nullptr);
  run["costs"] = end.costs;
  run["measure_costs_ms"] = end.measureCosts;
  run["interrupted"] = end.interrupted;
  run["totals"] = {{"ok", end.ok}, {"failed", end.failed}, {"skipped", end.skipped}, {"cases", end.cases}};
  run["validation_errors"] = end.validationErrors;
}

json mergedRunJson(const json& context, const json& mergedFrom, bool forced, const json& startTime,
                   const json& endTime) {
  return {{"schema_version", kSchemaVersion}, {"context", context}, {"merged_from", mergedFrom}, {"forced", forced},
          {"start_time", startTime},          {"end_time", endTime}};
}

}  // namespace lb
