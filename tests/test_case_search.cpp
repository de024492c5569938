// A matched case's search kept for a later invocation of the same run (replay/case_search.h): a
// sweep stopped by a deadline resumes without searching its unfinished cases again.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";
const std::string kSphere = "sphere_proc65s5_flyover_96x64_match-triangles3000_tuned";
const std::string kCdlod = "cdlod_proc65s5_flyover_96x64_match-triangles3000";

// Interleaved like the workload suite, one tuned and one plain matched scheme.
Config searchConfig() {
  return parseConfig(R"({
    "name": "search", "resolution": [96, 64], "grid": 8, "fps": 10, "warmup_frames": 0, "max_frames": 4,
    "repetitions": 2, "interleave": true,
    "terrain": {"type": "procedural", "size": 65, "seed": 5},
    "paths": ["paths/flyover.csv"],
    "schemes": [{"name": "sphere", "tune": {"grid": [4, 8]}}, "cdlod"],
    "match": {"metric": "triangles", "value": 3000, "frames": 3, "iterations": 8}
  })",
                     "search.json", kConfigs);
}

// Per process: ctest runs these tests in parallel processes, each making its own first run.
fs::path fresh(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / (name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  return d;
}

json readJson(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

void writeJson(const fs::path& p, const json& j) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << j.dump(1);
}

// The first run's records, shared by the tests (one search of each case).
const fs::path& firstRun() {
  static const fs::path d = [] {
    fs::path dir = fresh("case_search_first");
    EXPECT_EQ(runSweep(searchConfig(), {dir.string(), false, false}).ok, 2);
    return dir;
  }();
  return d;
}

}  // namespace

TEST(CaseSearch, EveryMatchedCaseKeepsItsSearchWithItsDigest) {
  for (const std::string& id : {kSphere, kCdlod}) {
    json c = readJson(firstRun() / "cases" / (id + ".json"));
    json s = readJson(firstRun() / "searches" / (id + ".json"));
    EXPECT_EQ(s["digest"], c["digest"]) << id;
    EXPECT_EQ(s["params"], c["params"]) << id;
    EXPECT_EQ(s["matched"], c["matched"]) << id;
    EXPECT_FALSE(c["matched"].contains("checkpoint")) << id;
  }
  // The tuned search's choice of grid is kept with it.
  json sphere = readJson(firstRun() / "searches" / (kSphere + ".json"));
  EXPECT_EQ(sphere["grid"], sphere["matched"]["tuned"]["chosen"]["grid"]);
}

TEST(CaseSearch, ACheckpointOfTheSameCaseIsDrawnInsteadOfSearching) {
  // A planted checkpoint whose parameter no search would choose: the case draws it, says where
  // it came from, and the other case, without a checkpoint, searches as before.
  json planted = readJson(firstRun() / "searches" / (kSphere + ".json"));
  const double chosen = planted["params"]["tri_size"].get<double>();
  planted["params"]["tri_size"] = chosen * 3 + 1;
  planted["matched"]["value"] = chosen * 3 + 1;
  fs::path d = fresh("case_search_planted");
  writeJson(d / "searches" / (kSphere + ".json"), planted);
  EXPECT_EQ(runSweep(searchConfig(), {d.string(), false, false}).ok, 2);
  json sphere = readJson(d / "cases" / (kSphere + ".json"));
  EXPECT_EQ(sphere["params"]["tri_size"].get<double>(), chosen * 3 + 1);
  EXPECT_TRUE(sphere["matched"].contains("checkpoint"));
  // Drawn, not only recorded: larger triangles, fewer of them.
  json sphereFirst = readJson(firstRun() / "cases" / (kSphere + ".json"));
  EXPECT_LT(sphere["summary"]["triangles"]["median"].get<double>(),
            sphereFirst["summary"]["triangles"]["median"].get<double>() / 2);
  json cdlod = readJson(d / "cases" / (kCdlod + ".json"));
  json cdlodFirst = readJson(firstRun() / "cases" / (kCdlod + ".json"));
  EXPECT_FALSE(cdlod["matched"].contains("checkpoint"));
  EXPECT_EQ(cdlod["params"], cdlodFirst["params"]);
  EXPECT_EQ(cdlod["matched"], cdlodFirst["matched"]);
}

TEST(CaseSearch, ACheckpointOfOtherInputsOrUnreadableIsSearchedAgain) {
  // Another digest (the case's inputs changed) and a truncated file: both cases search anew and
  // their checkpoints are rewritten with this run's search.
  json other = readJson(firstRun() / "searches" / (kSphere + ".json"));
  other["digest"] = std::string(64, '0');
  other["params"]["tri_size"] = 1000.0;
  fs::path d = fresh("case_search_stale");
  writeJson(d / "searches" / (kSphere + ".json"), other);
  std::ofstream(d / "searches" / (kCdlod + ".json")) << "{\"digest\": ";
  EXPECT_EQ(runSweep(searchConfig(), {d.string(), false, false}).ok, 2);
  for (const std::string& id : {kSphere, kCdlod}) {
    json c = readJson(d / "cases" / (id + ".json"));
    json first = readJson(firstRun() / "cases" / (id + ".json"));
    EXPECT_FALSE(c["matched"].contains("checkpoint")) << id;
    EXPECT_NE(c["params"]["tri_size"], 1000.0) << id;
    // cdlod's search matches triangles alone, so it is deterministic; the tuned search also
    // weighs measured costs, which vary from run to run.
    if (id == kCdlod) EXPECT_EQ(c["params"], first["params"]);
    EXPECT_EQ(readJson(d / "searches" / (id + ".json"))["digest"], c["digest"]) << id;
  }
}
