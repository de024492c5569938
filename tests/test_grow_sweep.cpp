// Sweeps that grow: re-running a config with the same --out after adding a scheme runs
// only the new cases; a finished case whose inputs changed is refused until --rerun-changed; a
// case no longer in the config is stale: kept on disk, listed in run.json and left out of its cases,
// summary.json, frames.csv and the report; a folder of another tool version is refused. Cases
// record every parameter with its resolved value, and that enters the digest.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "cli_run.h"
#include "config/config.h"
#include "error.h"
#include "number_text.h"
#include "report/report.h"
#include "results/run_dir.h"
#include "schemes/registry.h"
#include "sweep/runner.h"
#include "version.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";
const std::string kUniform = "uniform-level3_proc33s5_flyover_48x32";
const std::string kSphere = "sphere_proc33s5_flyover_48x32";
const std::string kDistance = "distance_proc33s5_flyover_48x32";

fs::path fresh(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / "lodbench_grow" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Three frames at 48x32 on a 4x4 grid: each case takes a fraction of a second on lavapipe.
Config config(const std::string& schemes, int maxFrames = 3) {
  return parseConfig(R"({"name": "grow", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0,
                         "max_frames": )" +
                         std::to_string(maxFrames) + R"(, "terrain": {"type": "procedural", "size": 33, "seed": 5},
                         "paths": ["paths/flyover.csv"], "schemes": [)" +
                         schemes + "]}",
                     "grow.json", kConfigs);
}

RunOptions at(const fs::path& run, bool rerunChanged = false) {
  RunOptions o{run.string(), false, false};
  o.rerunChanged = rerunChanged;
  return o;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The run directory `run` prints on stdout (a line of its own, beside stderr's summary).
std::string trimmed(const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("results/", 0) == 0) return line;
  return "";
}

std::vector<std::string> ids(const json& array) {
  std::vector<std::string> out;
  for (auto& v : array) out.push_back(v.get<std::string>());
  return out;
}

}  // namespace

TEST(GrowSweep, AddedSchemeIsTheOnlyCaseThatRuns) {
  fs::path run = fresh("add") / "run";
  const std::string one = R"({"name": "uniform", "params": {"level": 3}})";
  RunTotals t = runSweep(config(one), at(run));
  ASSERT_EQ(t.ok, 1);
  const std::string kept = slurp(run / "cases" / (kUniform + ".json"));

  t = runSweep(config(one + R"(, "sphere")"), at(run));
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.resumed, 1) << "uniform kept, only sphere ran";
  EXPECT_EQ(slurp(run / "cases" / (kUniform + ".json")), kept) << "the kept case is byte for byte untouched";
  json rj = readRunJson(run.string());
  EXPECT_EQ(ids(rj["case_ids"]), (std::vector<std::string>{kUniform, kSphere}));
  EXPECT_TRUE(rj["stale_cases"].empty());
  EXPECT_EQ(rj["totals"]["ok"], 2);
  // The costs of the first invocation's scheme stay beside the new one's (dry-run estimates read them).
  EXPECT_TRUE(rj["costs"].contains("uniform")) << rj["costs"].dump();
  EXPECT_TRUE(rj["costs"].contains("sphere")) << rj["costs"].dump();
  EXPECT_EQ(readJsonFile((run / "summary.json").string())["cases"].size(), 2u);
}

// A setting every case shares keeps the case ids and changes the digests: refused, naming the
// cases and the field, until --rerun-changed.
TEST(GrowSweep, ChangedSettingIsRefusedThenRerunWithRerunChanged) {
  fs::path run = fresh("changed") / "run";
  const std::string schemes = R"({"name": "uniform", "params": {"level": 3}}, "sphere")";
  ASSERT_EQ(runSweep(config(schemes), at(run)).ok, 2);
  const std::string kept = slurp(run / "cases" / (kSphere + ".json"));

  std::string e = errorOf([&] { runSweep(config(schemes + R"(, "distance")", 4), at(run)); });
  EXPECT_NE(e.find("2 finished case(s) were run with other inputs"), std::string::npos) << e;
  EXPECT_NE(e.find(kSphere + ": measurement.max_frames (3 -> 4)"), std::string::npos) << e;
  EXPECT_NE(e.find("--rerun-changed"), std::string::npos) << e;
  EXPECT_EQ(slurp(run / "cases" / (kSphere + ".json")), kept) << "a refused run writes nothing";
  EXPECT_FALSE(fs::exists(run / "cases" / (kDistance + ".json"))) << "nor runs the new case";

  RunTotals t = runSweep(config(schemes + R"(, "distance")", 4), at(run, true));
  EXPECT_EQ(t.ok, 3);
  EXPECT_EQ(t.resumed, 0);
  json sphere = readJsonFile((run / "cases" / (kSphere + ".json")).string());
  EXPECT_EQ(sphere["frames"].size(), 4u);
  EXPECT_EQ(sphere["digest"], expandCases(config(schemes, 4))[1].digest);
  EXPECT_EQ(runSweep(config(schemes + R"(, "distance")", 4), at(run)).resumed, 3) << "unchanged now: all kept";
}

// Removing a scheme, or changing a listed parameter value (part of the case id), leaves its cases stale.
TEST(GrowSweep, RemovedSchemeIsStaleKeptOnDiskAndLeftOutOfTheRunAndTheReport) {
  fs::path run = fresh("stale") / "run";
  const std::string both = R"({"name": "uniform", "params": {"level": 3}}, "sphere")";
  ASSERT_EQ(runSweep(config(both), at(run)).ok, 2);
  const std::string sphereFile = slurp(run / "cases" / (kSphere + ".json"));

  RunTotals t = runSweep(config(R"({"name": "uniform", "params": {"level": 3}})"), at(run));
  EXPECT_EQ(t.ok, 1);
  EXPECT_EQ(t.resumed, 1);
  EXPECT_EQ(slurp(run / "cases" / (kSphere + ".json")), sphereFile) << "stale cases stay on disk as they were";
  json rj = readRunJson(run.string());
  EXPECT_EQ(ids(rj["case_ids"]), std::vector<std::string>{kUniform});
  EXPECT_EQ(ids(rj["stale_cases"]), std::vector<std::string>{kSphere});
  EXPECT_EQ(rj["totals"]["cases"], 1);
  json summary = readJsonFile((run / "summary.json").string());
  ASSERT_EQ(summary["cases"].size(), 1u);
  EXPECT_EQ(summary["cases"][0]["case_id"], kUniform);
  EXPECT_EQ(slurp(run / "frames.csv").find("sphere"), std::string::npos) << "no row of the stale case";
  EXPECT_EQ(readCaseFiles(run.string()).size(), 1u);
  EXPECT_EQ(readCaseFiles(run.string(), true).size(), 2u);

  ReportOptions ro;
  ro.runDir = run.string();
  ro.html = false;
  writeReport(ro);
  const std::string md = slurp(run / "report" / "report.md");
  EXPECT_NE(md.find(kUniform), std::string::npos);
  EXPECT_EQ(md.find(kSphere), std::string::npos) << "the report leaves the stale case out";

  // Back in the config, the stale case is kept again (its digest is unchanged), not rerun.
  t = runSweep(config(both), at(run));
  EXPECT_EQ(t.resumed, 2);
  EXPECT_TRUE(readRunJson(run.string())["stale_cases"].empty());
}

TEST(GrowSweep, FolderOfAnotherToolVersionOrDeviceIsRefused) {
  fs::path run = fresh("version") / "run";
  const std::string one = R"({"name": "uniform", "params": {"level": 3}})";
  ASSERT_EQ(runSweep(config(one), at(run)).ok, 1);
  json rj = readRunJson(run.string());
  const std::string original = rj.dump(2);
  rj["context"]["tool_version"] = "0.1.0";
  std::ofstream(run / "run.json") << rj.dump(2);
  const std::string e = errorOf([&] { runSweep(config(one + R"(, "sphere")"), at(run, true)); });
  EXPECT_NE(e.find("written by lodbench 0.1.0, this is lodbench " + std::string(kToolVersion)), std::string::npos) << e;
  EXPECT_NE(e.find("run into a new --out"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(run / "cases" / (kSphere + ".json"))) << "refused before any case ran";

  rj = json::parse(original);
  rj["context"]["device"] = "Some Other GPU";
  std::ofstream(run / "run.json") << rj.dump(2);
  const std::string d = errorOf([&] { runSweep(config(one), at(run)); });
  EXPECT_NE(d.find("was run with device \"Some Other GPU\""), std::string::npos) << d;
}

// Defaults enter the record: `params` holds every parameter, and a default given explicitly is the
// same case as one left out.
TEST(GrowSweep, CaseRecordsEveryParameterWithItsResolvedValue) {
  std::vector<Case> cases = expandCases(config(R"("sphere", {"name": "uniform", "params": {"level": 3}})"));
  ASSERT_EQ(cases.size(), 2u);
  const SchemeInfo& info = findScheme("sphere")->info();
  json expected = json::object();
  for (auto& p : info.params) expected[p.name] = p.defaultValue;
  EXPECT_EQ(cases[0].inputs["params"], expected);
  EXPECT_EQ(cases[0].id, kSphere) << "ids name the listed values only";
  EXPECT_EQ(cases[0].inputs["tool_version"], kToolVersion);

  const std::string e = errorOf([&] {
    expandCases(config(R"("sphere", {"name": "sphere", "params": {"tri_size": )" +
                       std::to_string(int(resolveParams(info, {}).at("tri_size"))) + "}}"));
  });
  EXPECT_NE(e.find("both run sphere"), std::string::npos) << e;

  fs::path run = fresh("params") / "run";
  ASSERT_EQ(runSweep(config(R"("sphere", {"name": "uniform", "params": {"level": 3}})"), at(run)).ok, 2);
  json sphere = readJsonFile((run / "cases" / (kSphere + ".json")).string());
  EXPECT_EQ(sphere["params"], expected);
  // frames.csv ends each row with the scheme and one column per parameter of the run.
  std::istringstream csv(slurp(run / "frames.csv"));
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header.substr(header.find(",scheme,")), ",scheme,param_integer,param_level,param_tri_size");
  std::getline(csv, row);
  EXPECT_EQ(row.substr(0, row.find(',')), kSphere);
  EXPECT_EQ(row.substr(row.rfind(",sphere,")), ",sphere,0,," + numberText(expected["tri_size"].get<double>()));
}

// A parameter listed at its default is the same case as one left out, and a run
// of either into the folder of the other keeps the case (same digest, the id it was recorded
// with), never marking it stale and running it again. Every parameter of every scheme, in both
// directions, through the resume plan (no device).
TEST(GrowSweep, EveryParameterListedAtItsDefaultKeepsTheCase) {
  const fs::path root = fresh("listed_default");
  // The one finished case of `cases` as `run` records it (what planResume reads of it).
  auto record = [](const fs::path& run, const Case& c) {
    fs::create_directories(run / "cases");
    json doc = {{"case_id", c.id},    {"digest", c.digest}, {"inputs", c.inputs},
                {"scheme", c.scheme}, {"status", "ok"},     {"frames", json::array()}};
    std::ofstream(run / "cases" / (c.id + ".json")) << doc.dump(1);
  };
  int checked = 0;
  for (const Scheme* scheme : allSchemes()) {
    const SchemeInfo& info = scheme->info();
    const std::vector<Case> bare = expandCases(config(json(info.name).dump()));
    ASSERT_EQ(bare.size(), 1u);
    for (const ParamSpec& p : info.params) {
      SCOPED_TRACE(info.name + " " + p.name + "=" + numberText(p.defaultValue));
      const json entry = {{"name", info.name}, {"params", {{p.name, p.defaultValue}}}};
      const std::vector<Case> listed = expandCases(config(entry.dump()));
      ASSERT_EQ(listed.size(), 1u);
      EXPECT_EQ(listed[0].digest, bare[0].digest) << "the same resolved parameters";
      EXPECT_NE(listed[0].id, bare[0].id) << "ids name the listed parameters (existing ids stay as they are)";
      // Left out first, then listed at its default; and the other way round.
      for (bool listedFirst : {false, true}) {
        const fs::path run = root / (info.name + "-" + p.name + (listedFirst ? "-listed" : "-bare"));
        const Case& first = listedFirst ? listed[0] : bare[0];
        record(run, first);
        std::vector<Case> now = listedFirst ? bare : listed;
        const ResumePlan plan = planResume(run.string(), now);
        EXPECT_EQ(plan.reuse, std::set<std::string>{first.id}) << "kept";
        EXPECT_TRUE(plan.stale.empty()) << plan.stale.front();
        EXPECT_TRUE(plan.changed.empty()) << plan.changed.front();
        EXPECT_EQ(now[0].id, first.id) << "the case keeps the id it was recorded with";
        ASSERT_EQ(plan.renamed.size(), 1u);
        EXPECT_NE(plan.renamed[0].find("listed now as"), std::string::npos) << plan.renamed[0];
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 2 * 20) << "every parameter of every scheme";

  // A case of other inputs is not taken for one: a listed value that is not the default stays
  // a new case beside a stale one.
  const fs::path run = root / "other-value";
  record(run, expandCases(config(R"("sphere")"))[0]);
  std::vector<Case> other = expandCases(config(R"({"name": "sphere", "params": {"tri_size": 9}})"));
  const ResumePlan plan = planResume(run.string(), other);
  EXPECT_TRUE(plan.reuse.empty());
  EXPECT_TRUE(plan.renamed.empty());
  EXPECT_EQ(plan.stale, std::vector<std::string>{kSphere});
  EXPECT_EQ(other[0].id.rfind("sphere-tri_size9_", 0), 0u) << other[0].id;
}

// The same through the binary, as the issue ran it: cdlod, then cdlod with morph 0.3 (its
// default) into the same --out: dry-run and run keep the one case; nothing is stale or runs.
TEST(GrowSweep, CdlodWithItsDefaultMorphListedResumesTheBareRun) {
  ASSERT_EQ(resolveParams(findScheme("cdlod")->info(), {}).at("morph"), 0.3) << "the issue's default";
  const fs::path dir = fresh("cdlod_morph");
  const std::string head = R"({"name": "morph", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0,
    "max_frames": 2, "terrain": {"type": "procedural", "size": 33, "seed": 5},
    "paths": [")" + kConfigs +
                           R"(/paths/flyover.csv", ")" + kConfigs + R"(/paths/lowalt.csv"], "schemes": [)";
  std::ofstream(dir / "bare.json") << head << R"("cdlod"]})";
  std::ofstream(dir / "listed.json") << head << R"({"name": "cdlod", "params": {"morph": 0.3}}]})";
  const std::string out = (dir / "run").string();
  lb::test::CliOut o = lb::test::lodbench("run " + (dir / "bare.json").string() + " --out " + out + " --quiet", false);
  ASSERT_EQ(o.code, 0) << o.text;
  const json before = readRunJson(out);
  ASSERT_EQ(before["case_ids"].size(), 2u);
  std::map<std::string, std::string> files;
  for (auto& e : fs::directory_iterator(out + "/cases")) files[e.path().string()] = slurp(e.path());

  o = lb::test::lodbench("run " + (dir / "listed.json").string() + " --out " + out + " --dry-run", false);
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("2 finished case(s) kept, 0 changed (refused without --rerun-changed), 0 stale, 0 to run"),
            std::string::npos)
      << o.text;
  for (auto& id : before["case_ids"]) EXPECT_NE(o.text.find(id.get<std::string>() + "\n"), std::string::npos) << o.text;

  o = lb::test::lodbench("run " + (dir / "listed.json").string() + " --out " + out, false);
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("2 ok (2 resumed)"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("keep the id they were recorded with"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("stale"), std::string::npos) << o.text;
  const json after = readRunJson(out);
  EXPECT_EQ(after["case_ids"], before["case_ids"]);
  EXPECT_TRUE(after["stale_cases"].empty());
  std::map<std::string, std::string> now;
  for (auto& e : fs::directory_iterator(out + "/cases")) now[e.path().string()] = slurp(e.path());
  EXPECT_TRUE(now == files) << "the case files are kept byte for byte, and no other is written";
  EXPECT_EQ(readJsonFile(out + "/summary.json")["cases"].size(), 2u);
}

// `run` without --out writes results/<name>/<utc-time>/ under the working directory: `latest`
// follows the newest; a folder given with --out (rounds, shards) gets none beside it.
TEST(GrowSweep, LatestPointsAtTheNewestDefaultRun) {
  fs::path cwd = fresh("latest");
  std::ofstream(cwd / "grow.json") << R"({"name": "grow", "resolution": [48, 32], "grid": 4, "fps": 10,
    "warmup_frames": 0, "max_frames": 2, "terrain": {"type": "procedural", "size": 33, "seed": 5},
    "paths": [")" + kConfigs + R"(/paths/flyover.csv"], "schemes": [{"name": "uniform", "params": {"level": 3}}]})";
  const std::string run =
      "cd '" + cwd.string() + "' && env -u LODBENCH_VALIDATION " + LODBENCH_BINARY + " run grow.json -q";
  lb::test::CliOut first = lb::test::shell(run);
  ASSERT_EQ(first.code, 0) << first.text;
  const fs::path latest = cwd / "results" / "grow" / "latest";
  ASSERT_TRUE(fs::is_symlink(latest));
  const fs::path firstId = fs::read_symlink(latest);
  EXPECT_EQ((cwd / trimmed(first.text)).lexically_normal(), (cwd / "results" / "grow" / firstId).lexically_normal());
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // run ids are UTC seconds
  lb::test::CliOut second = lb::test::shell(run);
  ASSERT_EQ(second.code, 0) << second.text;
  EXPECT_NE(fs::read_symlink(latest), firstId);
  EXPECT_EQ(fs::read_symlink(latest), fs::path(trimmed(second.text)).filename());
  EXPECT_TRUE(fs::exists(latest / "run.json"));

  fs::path rounds = fresh("latest_rounds") / "grow";
  runSweep(config(R"({"name": "uniform", "params": {"level": 3}})"), at(rounds / "r1"));
  EXPECT_FALSE(fs::exists(rounds / "latest"));
}
