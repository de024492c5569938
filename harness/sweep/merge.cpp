#include "sweep/merge.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "error.h"
#include "results/gbench_json.h"
#include "results/run_dir.h"
#include "results/run_json.h"
#include "results/write.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

MergeTotals mergeRuns(const std::string& outDir, const std::vector<std::string>& inputs, bool force) {
  if (inputs.empty()) throw InputError("merge: no run directories given");
  std::vector<json> runs;
  for (auto& d : inputs) runs.push_back(readRunJson(d));
  const json& first = runs[0]["context"];
  for (size_t i = 1; i < runs.size() && !force; ++i) {
    const json& c = runs[i]["context"];
    if (c["config"] != first["config"])
      throw InputError("merge: " + inputs[i] + " ran a different config than " + inputs[0] +
                       " (use --force to merge anyway)");
    for (const char* k : {"tool_version", "device", "driver", "driver_version"})
      if (c[k] != first[k])
        throw InputError(std::string("merge: ") + inputs[i] + " ran on " + k + " '" + c[k].dump() + "', " + inputs[0] +
                         " on '" + first[k].dump() + "' (use --force to merge anyway)");
  }
  fs::create_directories(outDir + "/cases");
  fs::create_directories(outDir + "/images");
  MergeTotals t;
  for (auto& d : inputs) {
    for (auto& cf : readCaseFiles(d)) {
      fs::path dst = fs::path(outDir) / "cases" / fs::path(cf.file).filename();
      if (fs::exists(dst)) {
        // Keep a finished copy over a failed one; otherwise the first shard's.
        json ja = readJsonFile(dst.string());
        ++t.duplicates;
        if (ja.value("status", "") == "ok" || cf.doc.value("status", "") != "ok") continue;
      } else {
        ++t.cases;
      }
      std::ifstream in(cf.file, std::ios::binary);
      writeFileAtomic(dst.string(), std::string(std::istreambuf_iterator<char>(in), {}));
    }
    if (fs::exists(d + "/images"))
      for (auto& e : fs::directory_iterator(d + "/images"))
        fs::copy_file(e.path(), fs::path(outDir) / "images" / e.path().filename(),
                      fs::copy_options::overwrite_existing);
  }
  json run = mergedRunJson(first, inputs, force, runs[0].value("start_time", ""));
  writeFileAtomic(outDir + "/run.json", run.dump(2));
  writeAggregates(outDir, first);
  writeGoogleBenchmarkJson(outDir);
  return t;
}

}  // namespace lb
