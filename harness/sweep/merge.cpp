#include "sweep/merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "error.h"
#include "results/gbench_json.h"
#include "results/run_dir.h"
#include "results/run_json.h"
#include "results/write.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Input {
  std::string dir;  // as named (lexically normal, no trailing slash): the smallest spelling of a folder named twice
  fs::path canonical;
  json run;
  std::vector<CaseFile> cases;
};

struct Copy {
  const Input* in = nullptr;
  const CaseFile* file = nullptr;
  std::string bytes;
  bool ok() const { return file->doc.value("status", "") == "ok"; }
};

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw InputError(p.string() + ": cannot open");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string displayName(const std::string& arg) {
  std::string s = fs::path(arg).lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s.empty() ? "." : s;
}

json field(const json& o, const char* k) {
  return o.is_object() && o.contains(k) ? o[k] : json();
}

// Which fields two copies of a case differ in: top-level keys, and inside `frames` and `summary`
// the keys of the records, so a re-run (timings only) reads as such.
std::string differingFields(const json& a, const json& b) {
  std::set<std::string> out;
  std::set<std::string> keys;
  for (auto& [k, v] : a.items()) keys.insert(k);
  for (auto& [k, v] : b.items()) keys.insert(k);
  for (auto& k : keys) {
    json x = field(a, k.c_str()), y = field(b, k.c_str());
    if (x == y) continue;
    if (k == "frames" && x.is_array() && y.is_array() && x.size() == y.size()) {
      for (size_t i = 0; i < x.size(); ++i)
        if (x[i].is_object() && y[i].is_object()) {
          for (auto& [fk, fv] : x[i].items())
            if (field(y[i], fk.c_str()) != fv) out.insert("frames[]." + fk);
          for (auto& [fk, fv] : y[i].items())
            if (!x[i].contains(fk)) out.insert("frames[]." + fk);
        } else if (x[i] != y[i]) {
          out.insert("frames");
        }
    } else if (k == "summary" && x.is_object() && y.is_object()) {
      for (auto& [sk, sv] : x.items())
        if (field(y, sk.c_str()) != sv) out.insert("summary." + sk);
      for (auto& [sk, sv] : y.items())
        if (!x.contains(sk)) out.insert("summary." + sk);
    } else {
      out.insert(k);
    }
  }
  std::string s;
  int n = 0;
  for (auto& f : out) {
    if (++n > 8) {
      s += ", ... (" + std::to_string(out.size() - 8) + " more)";
      break;
    }
    s += (s.empty() ? "" : ", ") + f;
  }
  return s.empty() ? "formatting only" : s;
}

// The images a case file lists (relative to its run directory), as names under images/.
std::vector<std::string> imagesOf(const json& doc) {
  std::vector<std::string> v;
  if (doc.contains("images") && doc["images"].is_array())
    for (auto& i : doc["images"])
      if (i.is_string()) v.push_back(i.get<std::string>());
  return v;
}

// "" when two byte-identical case files list images with the same bytes in both folders;
// otherwise the first image that differs.
std::string imageDifference(const Copy& a, const Copy& b) {
  for (auto& rel : imagesOf(a.file->doc)) {
    fs::path pa = fs::path(a.in->dir) / rel, pb = fs::path(b.in->dir) / rel;
    std::error_code ea, eb;
    bool ha = fs::is_regular_file(pa, ea), hb = fs::is_regular_file(pb, eb);
    if (ha != hb || (ha && readBytes(pa) != readBytes(pb))) return rel;
  }
  return "";
}

std::string caseFileOf(const Copy& c) {
  return (fs::path(c.in->dir) / "cases" / fs::path(c.file->file).filename()).string();
}

}  // namespace

MergeTotals mergeRuns(const std::string& outDir, const std::vector<std::string>& args, bool force) {
  if (args.empty()) throw InputError("merge: no run directories given");
  // The set of folders, in one order whatever the order and repetition of the arguments.
  std::vector<Input> inputs;
  for (auto& a : args) {
    std::error_code ec;
    fs::path canon = fs::weakly_canonical(a, ec);
    if (ec) canon = fs::absolute(a).lexically_normal();
    std::string name = displayName(a);
    auto it = std::find_if(inputs.begin(), inputs.end(), [&](const Input& i) { return i.canonical == canon; });
    if (it == inputs.end())
      inputs.push_back({name, canon, json(), {}});
    else
      it->dir = std::min(it->dir, name);
  }
  std::sort(inputs.begin(), inputs.end(),
            [](const Input& a, const Input& b) { return std::tie(a.dir, a.canonical) < std::tie(b.dir, b.canonical); });
  {
    std::error_code ec;
    fs::path outCanon = fs::weakly_canonical(outDir, ec);
    for (auto& in : inputs)
      if (!ec && in.canonical == outCanon)
        throw InputError("merge: --out " + outDir + " is one of the runs being merged; choose another folder");
  }
  for (auto& in : inputs) in.run = readRunJson(in.dir);

  const Input& ref = inputs[0];
  for (size_t i = 1; i < inputs.size() && !force; ++i) {
    const json &c = inputs[i].run["context"], &first = ref.run["context"];
    if (field(c, "config") != field(first, "config"))
      throw InputError("merge: " + inputs[i].dir + " ran a different config than " + ref.dir +
                       " (use --force to merge anyway)");
    for (const char* k : {"tool_version", "device", "driver", "driver_version"})
      if (field(c, k) != field(first, k))
        throw InputError(std::string("merge: ") + inputs[i].dir + " ran on " + k + " '" + field(c, k).dump() + "', " +
                         ref.dir + " on '" + field(first, k).dump() + "' (use --force to merge anyway)");
  }

  // Every copy of every case, in folder order.
  std::map<std::string, std::vector<Copy>> copies;
  for (auto& in : inputs) {
    in.cases = readCaseFiles(in.dir);
    for (auto& cf : in.cases) copies[cf.id()].push_back({&in, &cf, readBytes(cf.file)});
  }

  MergeTotals t;
  t.folders = int(inputs.size());
  std::vector<std::string> conflicts;
  std::vector<const Copy*> kept;
  for (auto& [id, all] : copies) {
    std::vector<const Copy*> candidates;
    for (auto& c : all)
      if (c.ok()) candidates.push_back(&c);
    const bool anyOk = !candidates.empty();
    if (!anyOk)
      for (auto& c : all) candidates.push_back(&c);
    const Copy* keep = candidates[0];
    for (size_t i = 1; i < candidates.size(); ++i) {
      const Copy* other = candidates[i];
      std::string why;
      if (other->bytes != keep->bytes)
        why = differingFields(keep->file->doc, other->file->doc);
      else if (std::string img = imageDifference(*keep, *other); !img.empty())
        why = "image " + img;
      if (why.empty()) continue;
      if (anyOk)
        conflicts.push_back("case " + id + ": " + caseFileOf(*keep) + " and " + caseFileOf(*other) + " differ (" + why +
                            ")");
      else
        t.notes.push_back("case " + id + ": kept the " + keep->file->doc.value("status", "unfinished") + " copy in " +
                          keep->in->dir + "; the " + other->file->doc.value("status", "unfinished") + " copy in " +
                          other->in->dir + " differs (" + why + ")");
    }
    if (anyOk)
      for (auto& c : all)
        if (!c.ok())
          t.notes.push_back("case " + id + ": kept the finished copy in " + keep->in->dir + " over the " +
                            c.file->doc.value("status", "unfinished") + " copy in " + c.in->dir);
    kept.push_back(keep);
    t.duplicates += int(all.size()) - 1;
  }
  if (!conflicts.empty()) {
    std::string list;
    for (size_t i = 0; i < conflicts.size() && i < 10; ++i) list += "\n  " + conflicts[i];
    if (conflicts.size() > 10) list += "\n  ... and " + std::to_string(conflicts.size() - 10) + " more";
    throw InputError("merge: " + std::to_string(conflicts.size()) +
                     " case(s) have two finished copies that differ:" + list +
                     "\na case measured twice (a shard run again into another folder) has two sets of timings, and "
                     "merge does not choose between them (--force does not either): leave one of the folders out, "
                     "or delete one copy of each case named");
  }

  fs::create_directories(outDir + "/cases");
  fs::create_directories(outDir + "/images");
  std::set<std::string> keptFiles;
  json caseIds = json::array();
  std::map<const Input*, json> idsFrom;
  for (const Copy* c : kept) {
    std::string name = fs::path(c->file->file).filename().string();
    keptFiles.insert(name);
    caseIds.push_back(c->file->id());
    auto& ids = idsFrom[c->in];
    if (ids.is_null()) ids = json::array();
    ids.push_back(c->file->id());
    writeFileAtomic((fs::path(outDir) / "cases" / name).string(), c->bytes);
    for (auto& rel : imagesOf(c->file->doc)) {
      fs::path src = fs::path(c->in->dir) / rel;
      std::error_code ec;
      if (fs::path(rel).parent_path() != "images" || !fs::is_regular_file(src, ec)) continue;
      writeFileAtomic((fs::path(outDir) / rel).string(), readBytes(src));
    }
  }
  t.cases = int(kept.size());

  // The run's context is that of the folder started first (then by name): a retry started later
  // leaves it as it was. Each folder's board and host are in merged_inputs.
  auto startOf = [](const Input& in) {
    json s = field(in.run, "start_time");
    return s.is_string() ? s.get<std::string>() : std::string("~");  // none: after every time
  };
  const Input* earliest = &inputs[0];
  for (auto& in : inputs)
    if (startOf(in) < startOf(*earliest)) earliest = &in;
  json from = json::array(), merged = json::array();
  std::string start, end;
  for (auto& in : inputs) {
    from.push_back(in.dir);
    const json& ctx = in.run["context"];
    merged.push_back({{"dir", in.dir},
                      {"shard", field(in.run, "shard")},
                      {"start_time", field(in.run, "start_time")},
                      {"end_time", field(in.run, "end_time")},
                      {"host", field(ctx, "host")},
                      {"device_uuid", field(ctx, "device_uuid")},
                      {"power_limit_w", field(ctx, "power_limit_w")},
                      {"power_limit_enforced_w", field(ctx, "power_limit_enforced_w")},
                      {"case_ids", idsFrom.count(&in) ? idsFrom[&in] : json::array()}});
    json s = field(in.run, "start_time"), e = field(in.run, "end_time");
    if (s.is_string() && (start.empty() || s.get<std::string>() < start)) start = s.get<std::string>();
    if (e.is_string() && e.get<std::string>() > end) end = e.get<std::string>();
  }
  // Case files already in the output folder that this merge did not write (an earlier merge's):
  // kept on disk, left out as a grown sweep's stale cases are.
  json stale = json::array();
  for (auto& cf : readCaseFiles(outDir, true))
    if (!keptFiles.count(fs::path(cf.file).filename().string())) stale.push_back(cf.id());
  const json& context = earliest->run["context"];
  json run = mergedRunJson(context, from, force, start.empty() ? json(nullptr) : json(start),
                           end.empty() ? json(nullptr) : json(end));
  run["merged_inputs"] = merged;
  run["case_ids"] = caseIds;
  if (!stale.empty()) run["stale_cases"] = stale;
  writeFileAtomic(outDir + "/run.json", run.dump(2));
  writeAggregates(outDir, context);
  writeGoogleBenchmarkJson(outDir);
  return t;
}

}  // namespace lb
