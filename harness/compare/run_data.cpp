#include "compare/run_data.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "error.h"
#include "metrics/stats.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

json readJsonFile(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open (" + (fs::exists(file) ? "unreadable" : "missing") + ")");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(file + ": not valid JSON: " + e.what());
  }
}

static void addCase(RunData& run, const std::string& file) try {
  json cj = readJsonFile(file);
  if (!cj.is_object() || !cj.contains("case_id") || !cj["case_id"].is_string())
    throw InputError(file + ": not a lodbench case file (no \"case_id\")");
  if (!cj.contains("frames") || !cj["frames"].is_array())
    throw InputError(file + ": not a lodbench case file (no \"frames\" array)");
  CaseData c;
  c.id = cj["case_id"].get<std::string>();
  c.file = file;
  c.status = cj.value("status", "ok");
  c.reason = cj.value("reason", "");
  c.frames = cj["frames"];
  if (cj.contains("summary") && cj["summary"].is_object()) c.summary = cj["summary"];
  if (c.status == "ok") {
    c.rounds = 1;
    for (auto& f : c.frames)
      if (f.contains("gpu_ms") && f["gpu_ms"].is_number()) c.gpuMs.push_back(f["gpu_ms"].get<double>());
    if (!c.gpuMs.empty()) c.roundMedians.push_back(percentile(c.gpuMs, 50));
  }
  if (run.cases.count(c.id)) throw InputError(file + ": case_id '" + c.id + "' appears in two case files");
  run.cases[c.id] = std::move(c);
} catch (const json::exception& e) {  // a field of the wrong type: untrusted input, not a bug
  throw InputError(file + ": " + e.what());
}

RunData loadRun(const std::string& dir) {
  if (!fs::is_directory(dir)) throw InputError(dir + ": no such run directory");
  RunData run;
  run.dir = dir;
  json rj = readJsonFile(dir + "/run.json");
  if (!rj.is_object() || !rj.contains("context") || !rj["context"].is_object())
    throw InputError(dir + "/run.json: not a lodbench run file (no \"context\" object)");
  run.context = rj["context"];
  if (rj.contains("test_slowdown") && rj["test_slowdown"].is_number()) run.testSlowdown = rj["test_slowdown"];
  std::vector<fs::path> files;
  if (fs::is_directory(dir + "/cases"))
    for (auto& e : fs::directory_iterator(dir + "/cases"))
      if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (auto& f : files) addCase(run, f.string());
  return run;
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
