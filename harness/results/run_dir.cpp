#include "results/run_dir.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "config/case_identity.h"
#include "config/config.h"
#include "error.h"
#include "results/write.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

json readJsonFile(const std::string& file) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw InputError(file + ": is a directory, not a JSON file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open (" + (fs::exists(file, ec) ? "unreadable" : "missing") + ")");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(file + ": not valid JSON: " + e.what());
  }
}

bool hasRunJson(const std::string& dir) {
  std::error_code ec;
  return fs::exists(dir + "/run.json", ec);
}

json readRunJson(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": no such run directory");
  json rj = readJsonFile(dir + "/run.json");
  if (!rj.is_object() || !rj.contains("context") || !rj["context"].is_object())
    throw InputError(dir + "/run.json: not a lodbench run file (no \"context\" object)");
  return rj;
}

std::vector<CaseFile> readCaseFiles(const std::string& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(dir + "/cases", ec))
    for (auto& e : fs::directory_iterator(dir + "/cases"))
      if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::vector<CaseFile> out;
  std::map<std::string, std::string> seen;  // case_id -> file
  for (auto& f : files) {
    CaseFile c{f.string(), readJsonFile(f.string())};
    const json& d = c.doc;
    if (!d.is_object() || !d.contains("case_id") || !d["case_id"].is_string())
      throw InputError(c.file + ": not a lodbench case file (no string \"case_id\")");
    if (!d.contains("frames") || !d["frames"].is_array())
      throw InputError(c.file + ": not a lodbench case file (no \"frames\" array)");
    if (d.contains("status") && !d["status"].is_string()) throw InputError(c.file + ": field 'status' is not a string");
    auto [it, fresh] = seen.emplace(c.id(), c.file);
    if (!fresh) throw InputError(c.file + ": case_id '" + c.id() + "' also appears in " + it->second);
    out.push_back(std::move(c));
  }
  return out;
}

// frames.csv and summary.json are rebuilt from the case files, so resumed runs stay complete.
void writeAggregates(const std::string& dir, const json& context) {
  std::string csv = framesCsvHeader();
  json cases = json::array();
  for (auto& cf : readCaseFiles(dir)) {
    const json& cj = cf.doc;
    auto field = [&](const char* k) { return cj.contains(k) ? cj[k] : json(); };
    json terrain = field("terrain");
    cases.push_back({{"case_id", cj["case_id"]},
                     {"scheme", field("scheme")},
                     {"params", field("params")},
                     {"terrain", terrain.is_object() && terrain.contains("label") ? terrain["label"] : terrain},
                     {"path", field("path")},
                     {"resolution", field("resolution")},
                     {"status", field("status")},
                     {"reason", field("reason")},
                     {"digest", field("digest")},
                     {"summary", field("summary")}});
    csv += framesCsvRows(cj);
  }
  writeFileAtomic(dir + "/frames.csv", csv);
  json summary = {{"schema_version", kSchemaVersion}, {"context", context}, {"cases", cases}};
  writeFileAtomic(dir + "/summary.json", summary.dump(2));
}

ResumePlan planResume(const std::string& dir, const std::vector<Case>& cases) {
  ResumePlan plan;
  std::map<std::string, const Case*> byId;
  for (auto& c : cases) byId[c.id] = &c;
  for (auto& cf : readCaseFiles(dir)) {
    auto it = byId.find(cf.id());
    if (it == byId.end()) {
      plan.foreign.push_back(cf.file);
      continue;
    }
    const Case& c = *it->second;
    if (cf.doc.value("status", "") != "ok") continue;  // failed or skipped: run again
    std::string recorded =
        cf.doc.contains("digest") && cf.doc["digest"].is_string() ? cf.doc["digest"].get<std::string>() : "";
    if (recorded == c.digest) {
      plan.reuse.insert(c.id);
      continue;
    }
    std::string what = cf.doc.contains("inputs") ? describeInputChange(cf.doc["inputs"], c.inputs)
                                                 : "recorded without an input digest (older lodbench)";
    plan.changed.push_back(c.id + ": " + (what.empty() ? "digest differs" : what));
  }
  return plan;
}

static std::string list(const std::vector<std::string>& items) {
  std::string s;
  for (size_t i = 0; i < items.size() && i < 10; ++i) s += "\n  " + items[i];
  if (items.size() > 10) s += "\n  ... and " + std::to_string(items.size() - 10) + " more";
  return s;
}

ResumePlan checkResume(const std::string& dir, const json& previous, const json& configRaw, int shardIndex,
                       int shardCount, const std::vector<Case>& cases, bool rerunChanged) {
  const std::string runJson = dir + "/run.json";
  const json& ctx = previous["context"];
  if (!ctx.contains("config") || ctx["config"] != configRaw)
    throw InputError(
        runJson + ": this run directory holds a different config ('" +
        (ctx.contains("config_file") && ctx["config_file"].is_string() ? ctx["config_file"].get<std::string>() : "?") +
        "'); choose another --out");
  int oldIndex = 0, oldCount = 1;
  if (previous.contains("shard") && previous["shard"].is_object()) {
    oldIndex = previous["shard"].value("index", 0);
    oldCount = previous["shard"].value("count", 1);
  }
  if (oldIndex != shardIndex || oldCount != shardCount)
    throw InputError(runJson + ": this run directory holds shard " + std::to_string(oldIndex) + "/" +
                     std::to_string(oldCount) + ", not " + std::to_string(shardIndex) + "/" +
                     std::to_string(shardCount) + " (--shard must match the folder's; choose another --out)");
  ResumePlan plan = planResume(dir, cases);
  if (!rerunChanged && (!plan.changed.empty() || !plan.foreign.empty())) {
    std::string msg = dir + ": cannot resume: ";
    if (!plan.changed.empty())
      msg += std::to_string(plan.changed.size()) + " finished case(s) were run with other inputs:" + list(plan.changed);
    if (!plan.foreign.empty())
      msg += std::string(plan.changed.empty() ? "" : "\n") + std::to_string(plan.foreign.size()) +
             " case file(s) belong to no case of this config and shard:" + list(plan.foreign);
    throw InputError(msg + "\n(run again with --rerun-changed to rerun changed cases and remove foreign case files)");
  }
  for (auto& c : plan.changed) std::fprintf(stderr, "lodbench: rerunning changed case %s\n", c.c_str());
  for (auto& f : plan.foreign) {
    std::fprintf(stderr, "lodbench: removing case file of no case of this run: %s\n", f.c_str());
    fs::remove(f);
  }
  return plan;
}

}  // namespace lb
