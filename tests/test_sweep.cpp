// Sweeps: sharding + merge equals an unsharded run; kills lose no finished case; resume.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "config/config.h"
#include "error.h"
#include "sweep/merge.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

Config sweepConfig(int maxFrames = 3) {
  return parseConfig(R"({
    "name": "shards", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0, "max_frames": )" +
                         std::to_string(maxFrames) + R"(,
    "terrain": {"type": "procedural", "size": 33, "seed": 5},
    "paths": ["paths/flyover.csv", "paths/horizon.csv"],
    "schemes": [{"name": "uniform", "params": {"level": [2, 3]}}, "sphere", "distance"]
  })",
                     "shards.json", kConfigs);
}

fs::path fresh(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  return d;
}

json readJson(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

// case id -> per-frame counters
std::map<std::string, std::vector<std::vector<uint64_t>>> counters(const fs::path& dir) {
  std::map<std::string, std::vector<std::vector<uint64_t>>> out;
  for (auto& e : fs::directory_iterator(dir / "cases")) {
    json c = readJson(e.path());
    auto& frames = out[c["case_id"]];
    for (auto& f : c["frames"])
      frames.push_back({f["patches"], f["tes_invocations"], f["clip_invocations"], f["fragment_invocations"]});
  }
  return out;
}

}  // namespace

TEST(Sweep, ShardsPartitionTheCasesDeterministically) {
  Config c = sweepConfig();
  auto all = expandCases(c);
  ASSERT_EQ(all.size(), 2u * 4u);
  std::set<std::string> seen;
  for (int i = 0; i < 3; ++i)
    for (auto& k : shardCases(c, i, 3)) EXPECT_TRUE(seen.insert(k.id).second) << k.id;
  EXPECT_EQ(seen.size(), all.size());
  EXPECT_EQ(shardCases(c, 1, 3)[0].id, shardCases(c, 1, 3)[0].id);
  // Two workloads (one terrain x two paths) over two shards: each shard holds one whole workload,
  // so every scheme of it runs on the same device.
  for (int s = 0; s < 2; ++s) {
    auto part = shardCases(c, s, 2);
    ASSERT_EQ(part.size(), 4u);
    for (auto& k : part) EXPECT_EQ(k.path, part[0].path) << k.id;
  }
  EXPECT_NE(shardCases(c, 0, 2)[0].path, shardCases(c, 1, 2)[0].path);
  // More shards than workloads: blocks of cases, none left out, none empty.
  seen.clear();
  for (int s = 0; s < 3; ++s) {
    auto part = shardCases(c, s, 3);
    EXPECT_FALSE(part.empty());
    for (auto& k : part) seen.insert(k.id);
  }
  EXPECT_EQ(seen.size(), all.size());
  int i = 0, n = 0;
  EXPECT_THROW(parseShard("3/3", i, n), InputError);
  EXPECT_THROW(parseShard("x", i, n), InputError);
  parseShard("2/5", i, n);
  EXPECT_EQ(i, 2);
  EXPECT_EQ(n, 5);
}

TEST(Sweep, MergedShardsEqualAnUnshardedRun) {
  Config c = sweepConfig();
  fs::path whole = fresh("sweep_whole"), s0 = fresh("sweep_s0"), s1 = fresh("sweep_s1"), merged = fresh("sweep_merged");
  EXPECT_EQ(runSweep(c, {whole.string(), false, false}).ok, 8);
  RunOptions o0{s0.string(), false, false, 0, 2}, o1{s1.string(), false, false, 1, 2};
  EXPECT_EQ(runSweep(c, o0).ok, 4);
  EXPECT_EQ(runSweep(c, o1).ok, 4);
  MergeTotals t = mergeRuns(merged.string(), {s0.string(), s1.string()}, false);
  EXPECT_EQ(t.cases, 8);
  EXPECT_EQ(t.duplicates, 0);
  EXPECT_EQ(counters(merged), counters(whole)) << "same case set and same counters";
  EXPECT_EQ(readJson(merged / "summary.json")["cases"].size(), 8u);
}

TEST(Sweep, MergeRefusesDifferentConfigsUnlessForced) {
  Config a = sweepConfig(), b = sweepConfig(2);
  fs::path da = fresh("sweep_cfg_a"), db = fresh("sweep_cfg_b"), out = fresh("sweep_cfg_out");
  runSweep(a, {da.string(), false, false, 0, 4});
  runSweep(b, {db.string(), false, false, 1, 4});
  try {
    mergeRuns(out.string(), {da.string(), db.string()}, false);
    FAIL() << "merged different configs";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("different config"), std::string::npos) << e.what();
  }
  EXPECT_EQ(mergeRuns(out.string(), {da.string(), db.string()}, true).cases, 4);
  EXPECT_THROW(mergeRuns(out.string(), {"/nonexistent/run"}, false), InputError);
}

TEST(Sweep, ResumeRefusesADifferentConfig) {
  fs::path d = fresh("sweep_resume_cfg");
  runSweep(sweepConfig(), {d.string(), false, false, 0, 8});
  EXPECT_THROW(runSweep(sweepConfig(2), {d.string(), false, false, 0, 8}), InputError);
}

// Kill the CLI mid-sweep (SIGKILL, then SIGINT): finished cases survive intact, no temp files
// remain after a resume, and the resumed run has every case.
TEST(Sweep, KilledSweepLosesNoFinishedCaseAndResumes) {
  fs::path d = fresh("sweep_kill");
  fs::create_directories(d);
  std::string cfg = (d / "kill.json").string();
  std::ofstream(cfg) << R"({"name": "kill", "resolution": [64, 48], "grid": 8, "fps": 30, "warmup_frames": 0,
    "terrain": {"type": "procedural", "size": 65, "seed": 2},
    "paths": [")" + kConfigs +
                            R"(/paths/flyover.csv"],
    "schemes": [{"name": "uniform", "params": {"level": [2, 3, 4, 5, 6, 7]}}]})";
  fs::path run = d / "run";
  for (int sig : {SIGKILL, SIGINT}) {
    pid_t pid = fork();
    if (pid == 0) {
      execl(LODBENCH_BINARY, LODBENCH_BINARY, "run", cfg.c_str(), "--out", run.c_str(), "-q", (char*)nullptr);
      _exit(127);
    }
    // Wait until at least one more case has finished, then kill mid-case.
    size_t before = fs::exists(run / "cases") ? size_t(std::distance(fs::directory_iterator(run / "cases"), {})) : 0;
    for (int i = 0; i < 600; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      size_t n = fs::exists(run / "cases") ? size_t(std::distance(fs::directory_iterator(run / "cases"), {})) : 0;
      if (n > before) break;
    }
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    if (sig == SIGINT && WIFEXITED(status)) {
      EXPECT_TRUE(WEXITSTATUS(status) == 130 || WEXITSTATUS(status) == 0) << WEXITSTATUS(status);
    }
    for (auto& e : fs::directory_iterator(run / "cases")) {
      if (e.path().extension() != ".json") continue;
      json c = readJson(e.path());  // throws on a corrupt file
      EXPECT_EQ(c["status"], "ok");
    }
  }
  pid_t pid = fork();
  if (pid == 0) {
    execl(LODBENCH_BINARY, LODBENCH_BINARY, "run", cfg.c_str(), "--out", run.c_str(), "-q", (char*)nullptr);
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  json summary = readJson(run / "summary.json");
  EXPECT_EQ(summary["cases"].size(), 6u);
  json r = readJson(run / "run.json");
  EXPECT_GE(r["resumed_at"].size(), 1u);
  for (auto& e : fs::recursive_directory_iterator(run))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(Sweep, MatchedComparisonHitsTheTriangleBudget) {
  Config c = parseConfig(R"({
    "name": "match", "resolution": [96, 64], "grid": 8, "fps": 10, "warmup_frames": 0, "max_frames": 6,
    "terrain": {"type": "procedural", "size": 65, "seed": 5},
    "paths": ["paths/flyover.csv"],
    "schemes": ["uniform", "sphere", "reference"],
    "match": {"metric": "triangles", "value": 3000, "frames": 3, "iterations": 12}
  })",
                         "match.json", kConfigs);
  fs::path d = fresh("sweep_match");
  EXPECT_EQ(runSweep(c, {d.string(), false, false}).ok, 3);
  json sphere = readJson(d / "cases" / "sphere_proc65s5_flyover_96x64_match-triangles3000.json");
  EXPECT_EQ(sphere["matched"]["param"], "tri_size");
  EXPECT_TRUE(sphere["matched"]["reachable"].get<bool>());
  EXPECT_NEAR(sphere["matched"]["achieved"].get<double>(), 3000.0, 3000.0 * 0.1);
  EXPECT_EQ(sphere["params"]["tri_size"], sphere["matched"]["value"]);
  // uniform: 64 patches x 2 L^2 triangles; L = 5 gives 3200, the closest to 3000 (L = 4: 2048).
  json uniform = readJson(d / "cases" / "uniform_proc65s5_flyover_96x64_match-triangles3000.json");
  EXPECT_EQ(uniform["matched"]["value"], 5.0);
  EXPECT_EQ(uniform["summary"]["triangles"]["median"], 3200.0);
  // reference has no parameter to search: it runs as configured.
  json reference = readJson(d / "cases" / "reference_proc65s5_flyover_96x64_match-triangles3000.json");
  EXPECT_EQ(reference["matched"]["param"], "");
}
