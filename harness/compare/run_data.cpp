#include "compare/run_data.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "error.h"
#include "results/run_dir.h"
#include "stats.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

static void addCase(RunData& run, const CaseFile& cf) try {
  const json& cj = cf.doc;
  CaseData c;
  readCaseRecord(c, cj);
  c.id = cf.id();
  c.file = cf.file;
  c.status = cj.value("status", "ok");
  c.reason = cj.value("reason", "");  // of the wrong type: an error here, as for every field compare needs
  c.frames = cj["frames"];
  if (c.status == "ok") {
    c.rounds = 1;
    for (auto& f : c.frames)
      if (f.contains("gpu_ms") && f["gpu_ms"].is_number()) c.gpuMs.push_back(f["gpu_ms"].get<double>());
    if (!c.gpuMs.empty()) c.roundMedians.push_back(percentile(c.gpuMs, 50));
  }
  run.cases[c.id] = std::move(c);
} catch (const json::exception& e) {  // a field of the wrong type: untrusted input, not a bug
  throw InputError(cf.file + ": " + e.what());
}

RunData loadRun(const std::string& dir) {
  RunData run;
  run.dir = dir;
  json rj = readRunJson(dir);
  run.context = rj["context"];
  if (rj.contains("test_slowdown") && rj["test_slowdown"].is_number()) run.testSlowdown = rj["test_slowdown"];
  for (auto& cf : readCaseFiles(dir)) addCase(run, cf);
  return run;
}

std::vector<RunData> loadRounds(const std::string& dir) {
  if (hasRunJson(dir) || !fs::is_directory(dir)) return {loadRun(dir)};
  std::vector<std::string> rounds;
  for (auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && !e.is_symlink() && hasRunJson(e.path().string()))  // not `latest`: no round twice
      rounds.push_back(e.path().string());
  if (rounds.empty())
    throw InputError(dir + ": neither a run directory (run.json) nor a folder of rounds (*/run.json)");
  // r1, r2, ..., r10 in numeric order.
  std::sort(rounds.begin(), rounds.end(), [](const std::string& a, const std::string& b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
  });
  std::vector<RunData> out;
  for (auto& r : rounds) out.push_back(loadRun(r));
  return out;
}

RunData poolRuns(const std::vector<RunData>& rounds) {
  if (rounds.empty()) return {};
  RunData pooled = rounds.front();
  for (size_t i = 1; i < rounds.size(); ++i) {
    pooled.dir += ", " + rounds[i].dir;
    for (auto& [id, c] : rounds[i].cases) {
      auto it = pooled.cases.find(id);
      if (it == pooled.cases.end()) {
        pooled.cases[id] = c;
        continue;
      }
      CaseData& p = it->second;
      if (c.status != "ok") {  // a failure in any round is the side's failure: never hide it
        if (p.status == "ok") {
          p.status = c.status;
          p.reason = "round " + std::to_string(i + 1) + ": " + c.reason;
        }
        continue;
      }
      if (p.status != "ok") continue;
      p.gpuMs.insert(p.gpuMs.end(), c.gpuMs.begin(), c.gpuMs.end());
      p.rounds += c.rounds;
      p.roundMedians.insert(p.roundMedians.end(), c.roundMedians.begin(), c.roundMedians.end());
    }
  }
  return pooled;
}

}  // namespace lb
