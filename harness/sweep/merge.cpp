#include "sweep/merge.h"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "error.h"
#include "sweep/gbench_json.h"
#include "sweep/results.h"
#include "sweep/runner.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

static json readRun(const std::string& dir) {
  std::string file = dir + "/run.json";
  std::ifstream in(file);
  if (!in) throw InputError("cannot open " + file + " (not a lodbench run directory?)");
  json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("context")) throw InputError(file + ": not a valid run.json");
  return j;
}

MergeTotals mergeRuns(const std::string& outDir, const std::vector<std::string>& inputs, bool force) {
  if (inputs.empty()) throw InputError("merge: no run directories given");
  std::vector<json> runs;
  for (auto& d : inputs) runs.push_back(readRun(d));
  const json& first = runs[0]["context"];
  for (size_t i = 1; i < runs.size() && !force; ++i) {
    const json& c = runs[i]["context"];
    if (c["config"] != first["config"])
      throw InputError("merge: " + inputs[i] + " ran a different config than " + inputs[0] + " (use --force to merge anyway)");
    for (const char* k : {"device", "driver", "driver_version"})
      if (c[k] != first[k])
        throw InputError(std::string("merge: ") + inputs[i] + " ran on " + k + " '" + c[k].dump() + "', " + inputs[0] +
                         " on '" + first[k].dump() + "' (use --force to merge anyway)");
  }
  fs::create_directories(outDir + "/cases");
  fs::create_directories(outDir + "/images");
  MergeTotals t;
  for (auto& d : inputs) {
    for (auto& e : fs::directory_iterator(d + "/cases")) {
      if (e.path().extension() != ".json") continue;
      fs::path dst = fs::path(outDir) / "cases" / e.path().filename();
      if (fs::exists(dst)) {
        // Keep a finished copy over a failed one; otherwise the first shard's.
        std::ifstream a(dst), b(e.path());
        json ja = json::parse(a, nullptr, false), jb = json::parse(b, nullptr, false);
        ++t.duplicates;
        if (ja.value("status", "") == "ok" || jb.value("status", "") != "ok") continue;
      } else {
        ++t.cases;
      }
      std::ifstream in(e.path(), std::ios::binary);
      writeFileAtomic(dst.string(), std::string(std::istreambuf_iterator<char>(in), {}));
    }
    if (fs::exists(d + "/images"))
      for (auto& e : fs::directory_iterator(d + "/images"))
        fs::copy_file(e.path(), fs::path(outDir) / "images" / e.path().filename(), fs::copy_options::overwrite_existing);
  }
  json run = {{"schema_version", kSchemaVersion}, {"context", first}, {"merged_from", inputs}, {"forced", force},
              {"start_time", runs[0].value("start_time", "")}, {"end_time", isoTimeUtc()}};
  writeFileAtomic(outDir + "/run.json", run.dump(2));
  writeAggregates(outDir, first);
  writeGoogleBenchmarkJson(outDir);
  return t;
}

}  // namespace lb
