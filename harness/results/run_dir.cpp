#include "results/run_dir.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/case_identity.h"
#include "config/config.h"
#include "error.h"
#include "results/write.h"
#include "version.h"

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

// Case ids run.json lists as stale: files a grown sweep keeps on disk but no longer reports.
static std::set<std::string> staleCaseIds(const std::string& dir) {
  std::set<std::string> ids;
  if (!hasRunJson(dir)) return ids;
  json rj = readJsonFile(dir + "/run.json");
  if (rj.is_object() && rj.contains("stale_cases") && rj["stale_cases"].is_array())
    for (auto& id : rj["stale_cases"])
      if (id.is_string()) ids.insert(id.get<std::string>());
  return ids;
}

std::vector<CaseFile> readCaseFiles(const std::string& dir, bool includeStale) {
  const std::set<std::string> stale = includeStale ? std::set<std::string>() : staleCaseIds(dir);
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
    if (!stale.count(c.id())) out.push_back(std::move(c));
  }
  return out;
}

// frames.csv and summary.json are rebuilt from the case files, so resumed runs stay complete.
void writeAggregates(const std::string& dir, const json& context) {
  const std::vector<CaseFile> files = readCaseFiles(dir);
  std::set<std::string> names;  // every parameter of any case: one frames.csv column each
  for (auto& cf : files)
    if (cf.doc.contains("params") && cf.doc["params"].is_object())
      for (auto& [k, v] : cf.doc["params"].items()) names.insert(k);
  const std::vector<std::string> params(names.begin(), names.end());
  std::string csv = framesCsvHeader(params);
  json cases = json::array();
  for (auto& cf : files) {
    const json& cj = cf.doc;
    auto field = [&](const char* k) { return cj.contains(k) ? cj[k] : json(); };
    json terrain = field("terrain");
    cases.push_back({{"case_id", cj["case_id"]},
                     {"scheme", field("scheme")},
                     {"params", field("params")},
                     {"params_listed", field("params_listed")},
                     {"terrain", terrain.is_object() && terrain.contains("label") ? terrain["label"] : terrain},
                     {"path", field("path")},
                     {"resolution", field("resolution")},
                     {"status", field("status")},
                     {"reason", field("reason")},
                     {"digest", field("digest")},
                     {"summary", field("summary")}});
    csv += framesCsvRows(cj, params);
  }
  writeFileAtomic(dir + "/frames.csv", csv);
  json summary = {{"schema_version", kSchemaVersion}, {"context", context}, {"cases", cases}};
  writeFileAtomic(dir + "/summary.json", summary.dump(2));
}

ResumePlan planResume(const std::string& dir, std::vector<Case>& cases) {
  ResumePlan plan;
  std::vector<CaseFile> files = readCaseFiles(dir, true);  // a stale case back in the config is kept again
  std::map<std::string, size_t> byId;
  for (size_t i = 0; i < cases.size(); ++i) byId[cases[i].id] = i;
  std::set<std::string> recordedIds;
  for (auto& cf : files) recordedIds.insert(cf.id());
  // A case with no file of its id takes the first file (by name) of its digest that is of no case's
  // id and not taken yet: the same inputs under the id an earlier listing gave them.
  std::map<std::string, size_t> byDigest;
  for (size_t i = 0; i < cases.size(); ++i)
    if (!recordedIds.count(cases[i].id)) byDigest.emplace(cases[i].digest, i);
  for (auto& cf : files) {
    if (byId.count(cf.id())) continue;
    const json& d = cf.doc;
    auto it = d.contains("digest") && d["digest"].is_string() ? byDigest.find(d["digest"].get<std::string>())
                                                              : byDigest.end();
    if (it == byDigest.end()) continue;
    Case& c = cases[it->second];
    plan.renamed.push_back(cf.id() + " (listed now as " + c.id + ")");
    byId.erase(c.id);
    c.id = cf.id();
    byId[c.id] = it->second;
    byDigest.erase(it);
  }
  for (auto& cf : files) {
    auto it = byId.find(cf.id());
    if (it == byId.end()) {
      plan.stale.push_back(cf.id());
      continue;
    }
    const Case& c = cases[it->second];
    if (cf.doc.value("status", "") != "ok") continue;  // failed or skipped: run again
    std::string recorded =
        cf.doc.contains("digest") && cf.doc["digest"].is_string() ? cf.doc["digest"].get<std::string>() : "";
    if (recorded == c.digest) {
      plan.reuse.insert(c.id);
      continue;
    }
    std::string what = cf.doc.contains("inputs") ? describeInputChange(cf.doc["inputs"], c.inputs)
                                                 : "recorded without an input digest (older lodbench)";
    if (cf.doc.contains("inputs") && cf.doc["inputs"].is_object() && cf.doc["inputs"].contains("plugin") &&
        c.inputs.contains("plugin")) {
      json before = cf.doc["inputs"], now = c.inputs;
      before.erase("plugin");
      now.erase("plugin");
      if (before == now) {
        plan.rebuilt.push_back(c.id + ": " + what);
        continue;
      }
    }
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

void checkToolVersion(const std::string& dir, const json& previous) {
  const json& ctx = previous["context"];
  const std::string wrote = ctx.contains("tool_version") && ctx["tool_version"].is_string()
                                ? ctx["tool_version"].get<std::string>()
                                : "an unknown version";
  if (wrote == kToolVersion) return;
  throw InputError(dir + "/run.json: this run directory was written by lodbench " + wrote + ", this is lodbench " +
                   kToolVersion +
                   "; a parameter's, setting's or metric's meaning changed between them (docs/results-format.md, "
                   "Case identity), so its cases can be neither kept nor mixed with new ones: run into a new --out "
                   "(the old folder stays readable by report and compare), or finish it with lodbench " +
                   wrote);
}

ResumePlan checkResume(const std::string& dir, const json& previous, int shardIndex, int shardCount,
                       std::vector<Case>& cases, bool rerunChanged) {
  const std::string runJson = dir + "/run.json";
  checkToolVersion(dir, previous);
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
  if (!rerunChanged && !plan.changed.empty())
    throw InputError(dir + ": cannot resume: " + std::to_string(plan.changed.size()) +
                     " finished case(s) were run with other inputs:" + list(plan.changed) +
                     "\n(run again with --rerun-changed to run them again with the inputs of now)");
  for (auto& c : plan.changed) std::fprintf(stderr, "lodbench: rerunning changed case %s\n", c.c_str());
  for (auto& c : plan.rebuilt) std::fprintf(stderr, "lodbench: rerunning case of a rebuilt plugin %s\n", c.c_str());
  if (!plan.renamed.empty())
    std::fprintf(stderr,
                 "lodbench: %zu case(s) in %s keep the id they were recorded with (the same inputs: a parameter "
                 "listed at its default is the same case as one left out):%s\n",
                 plan.renamed.size(), dir.c_str(), list(plan.renamed).c_str());
  if (!plan.stale.empty())
    std::fprintf(stderr,
                 "lodbench: %zu stale case(s) in %s, no longer in the config (kept on disk, left out of run.json's "
                 "cases, summary.json, frames.csv and the report; listed in run.json \"stale_cases\"):%s\n",
                 plan.stale.size(), dir.c_str(), list(plan.stale).c_str());
  return plan;
}

void checkSameDevice(const std::string& dir, const json& previous, const json& context) {
  const json& was = previous["context"];
  for (const char* k : {"device", "driver", "driver_version"}) {
    const json a = was.contains(k) ? was[k] : json(), b = context.contains(k) ? context[k] : json();
    if (a != b)
      throw InputError(dir + "/run.json: this run directory was run with " + k + " " + a.dump() + ", this run has " +
                       b.dump() + "; one run holds one device's figures: choose another --out");
  }
}

}  // namespace lb
