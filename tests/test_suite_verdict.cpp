// The verdict's interval method (report/suite_verdict.h) on synthetic timings with known answers:
// a 95 % interval covers the true ratio about 95 % of the time, an exact copy ties, a scheme twice
// as slow loses with an interval that excludes 1, and the geometric mean over workloads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.h"
#include "compare/run_data.h"
#include "compare/suite_verdict.h"
#include "random.h"

using namespace lb;

namespace {

// Uniform in (0, 1) and a standard normal from the project's fully specified stream.
double uniform(SplitMix64& rng) {
  return (double(rng.next() >> 11) + 0.5) / 9007199254740992.0;
}
double normal(SplitMix64& rng) {
  return std::sqrt(-2 * std::log(uniform(rng))) * std::cos(6.283185307179586 * uniform(rng));
}

// A path whose frames cost `base` x a smooth per-frame profile (the same for every scheme), each
// repetition scaled by its own clock factor (sd `repSd`) and each frame by noise (sd `frameSd`).
SchemeTimings timings(const std::string& name, double base, int reps, int frames, double repSd, double frameSd,
                      SplitMix64& rng) {
  SchemeTimings s{name, {}, ""};
  for (int r = 0; r < reps; ++r) {
    const double clock = std::exp(repSd * normal(rng));
    std::vector<double> rep;
    for (int f = 0; f < frames; ++f) {
      const double profile = 1.0 + 0.5 * std::sin(f * 0.05);
      rep.push_back(base * profile * clock * std::exp(frameSd * normal(rng)));
    }
    s.reps.push_back(rep);
  }
  return s;
}

}  // namespace

TEST(SuiteVerdict, IntervalCoversTheTrueRatioAtItsStatedRate) {
  // 200 experiments, each a fresh draw of A (1 ms) and B (1.3 ms) timings: the 95 % interval of
  // B's ratio should hold 1.3 in about 95 % of them (binomial sd 1.5 %; 88 % is 4.6 sd below).
  SplitMix64 rng{42};
  int covered = 0, excludesOne = 0;
  const int experiments = 200;
  for (int e = 0; e < experiments; ++e) {
    Workload w{"synthetic", {timings("A", 1.0, 3, 120, 0.02, 0.05, rng), timings("B", 1.3, 3, 120, 0.02, 0.05, rng)}};
    SuiteVerdict v = suiteVerdict({w}, 0.95);
    const Interval& r = v.workloads[0].ratio.at("B");
    covered += r.lo <= 1.3 && 1.3 <= r.hi;
    excludesOne += r.lo > 1.0;
  }
  std::printf("[suite verdict] true ratio 1.3 inside the 95%% interval in %d of %d experiments\n", covered,
              experiments);
  EXPECT_GE(covered, int(0.88 * experiments));
  EXPECT_LE(covered, experiments);
  EXPECT_GE(excludesOne, int(0.95 * experiments)) << "a 30 % difference against 2 % clock noise is rarely a tie";
}

TEST(SuiteVerdict, AnExactCopyTiesAndADoubledCostLoses) {
  SplitMix64 rng{7};
  SchemeTimings sphere = timings("sphere", 1.0, 3, 100, 0.02, 0.05, rng);
  SchemeTimings copy = sphere;  // the same draws, as a registered exact copy measured alike
  copy.scheme = "sphere-copy";
  // An independent measurement of the same scheme: other noise, the same cost.
  SchemeTimings again = timings("sphere-again", 1.0, 3, 100, 0.02, 0.05, rng);
  SchemeTimings twice = sphere;  // every triangle drawn twice: twice the cost
  twice.scheme = "sphere-twice";
  for (auto& rep : twice.reps)
    for (double& t : rep) t *= 2;
  SuiteVerdict v = suiteVerdict({{"w", {sphere, copy, again, twice}}});
  const WorkloadResult& w = v.workloads[0];
  EXPECT_FALSE(w.verdict()) << "identical schemes must tie";
  auto tied = [&](const std::string& s) { return std::count(w.tied.begin(), w.tied.end(), s) == 1; };
  EXPECT_TRUE(tied("sphere-copy") && tied("sphere") && tied("sphere-again"));
  EXPECT_FALSE(tied("sphere-twice"));
  const Interval& t = w.ratio.at("sphere-twice");
  EXPECT_GT(t.lo, 1.0);
  EXPECT_LE(t.lo, 2.0 * 1.1);
  EXPECT_NEAR(t.value, 2.0, 0.1);
  nlohmann::json j = verdictJson(v);
  EXPECT_EQ(j["workloads"][0]["verdict"], "no verdict");
  for (const SchemeResult& s : v.schemes) {
    if (s.scheme == "sphere-twice") {
      EXPECT_EQ(s.wins + s.ties, 0);
    }
  }
}

// A 1.5 % difference with 0.1 % clock noise: a sure win without a margin, a tie within a 2 %
// margin, and still a win within a 1 % one.
TEST(SuiteVerdict, AMarginOfPracticalSignificanceTurnsSmallWinsIntoTies) {
  SplitMix64 rng{3};
  SchemeTimings a = timings("a", 1.0, 3, 100, 0.001, 0.01, rng);
  SchemeTimings b = timings("b", 1.015, 3, 100, 0.001, 0.01, rng);
  EXPECT_TRUE(suiteVerdict({{"w", {a, b}}}).workloads[0].verdict());
  EXPECT_GT(suiteVerdict({{"w", {a, b}}}).workloads[0].ratio.at("b").lo, 1.0);
  const SuiteVerdict within2 = suiteVerdict({{"w", {a, b}}}, 0.95, 0.02);
  EXPECT_FALSE(within2.workloads[0].verdict());
  EXPECT_EQ(within2.workloads[0].tied.size(), 2u);
  EXPECT_EQ(verdictJson(within2)["margin"], 0.02);
  EXPECT_EQ(verdictJson(within2)["workloads"][0]["verdict"], "no verdict");
  EXPECT_TRUE(suiteVerdict({{"w", {a, b}}}, 0.95, 0.01).workloads[0].verdict());
}

TEST(SuiteVerdict, GeometricMeanOverWorkloadsWinsAndMissingSchemes) {
  SplitMix64 rng{11};
  // A wins the first workload by 2x, B the second by 4x; C runs only the first, at 3x.
  Workload w1{"flat_flyover",
              {timings("A", 1.0, 3, 60, 0.01, 0.02, rng), timings("B", 2.0, 3, 60, 0.01, 0.02, rng),
               timings("C", 3.0, 3, 60, 0.01, 0.02, rng)}};
  Workload w2{"canyon_grazing",
              {timings("A", 4.0, 3, 60, 0.01, 0.02, rng), timings("B", 1.0, 3, 60, 0.01, 0.02, rng),
               SchemeTimings{"C", {}, "target unreachable: err_p95_px 1.52 at the finest level"}}};
  SuiteVerdict v = suiteVerdict({w1, w2});
  ASSERT_EQ(v.workloads.size(), 2u);
  EXPECT_EQ(v.workloads[0].cheapest, "A");
  EXPECT_EQ(v.workloads[1].cheapest, "B");
  EXPECT_TRUE(v.workloads[0].verdict() && v.workloads[1].verdict());
  std::map<std::string, SchemeResult> by;
  for (const SchemeResult& s : v.schemes) by[s.scheme] = s;
  // A: ratios 1 and 4 -> 2; B: 2 and 1 -> sqrt 2; C: 3 over the one workload it ran.
  EXPECT_NEAR(by["A"].geomean.value, 2.0, 0.05);
  EXPECT_NEAR(by["B"].geomean.value, std::sqrt(2.0), 0.05);
  EXPECT_NEAR(by["C"].geomean.value, 3.0, 0.1);
  EXPECT_LE(by["B"].geomean.lo, by["B"].geomean.value);
  EXPECT_GE(by["B"].geomean.hi, by["B"].geomean.value);
  EXPECT_EQ(by["A"].wins, 1);
  EXPECT_EQ(by["B"].wins, 1);
  EXPECT_EQ(by["C"].workloads, 1);
  ASSERT_EQ(by["C"].missingIn.size(), 1u);
  EXPECT_EQ(v.workloads[1].missing.at("C"), "target unreachable: err_p95_px 1.52 at the finest level");
  EXPECT_EQ(v.schemes.front().scheme, "B") << "ranked by geometric-mean ratio";
  // The same inputs and seed give the same intervals.
  SuiteVerdict again = suiteVerdict({w1, w2});
  EXPECT_EQ(verdictJson(v).dump(), verdictJson(again).dump());
}

TEST(SuiteVerdict, AnOverAccurateSchemeIsComparedWithANote) {
  // Missing: its finest setting errs more than the target; compared with a note: its coarsest
  // setting is already more accurate than the target, so it meets it at an upper bound of its cost.
  SplitMix64 rng{5};
  Workload w{"w",
             {timings("A", 1.0, 3, 30, 0.01, 0.02, rng), SchemeTimings{"B", {}, "target unreachable: ..."},
              timings("C", 2.0, 3, 30, 0.01, 0.02, rng)}};
  w.schemes[2].note = "more accurate than the target at its coarsest";
  SuiteVerdict v = suiteVerdict({w});
  const WorkloadResult& r = v.workloads[0];
  EXPECT_EQ(r.missing.count("B"), 1u);
  EXPECT_EQ(r.notes.at("C"), "more accurate than the target at its coarsest");
  EXPECT_NEAR(r.ratio.at("C").value, 2.0, 0.05);
  EXPECT_EQ(verdictJson(v)["workloads"][0]["notes"]["C"], "more accurate than the target at its coarsest");
}

TEST(SuiteVerdict, ASchemeAtAnUpperBoundOfItsCostIsNeverBeaten) {
  // C costs twice A's, far outside the interval; but its cost is an upper bound (its coarsest
  // setting is already more accurate than the target), so A's win over it is not established.
  SplitMix64 rng{6};
  Workload w{"w", {timings("A", 1.0, 3, 30, 0.01, 0.02, rng), timings("C", 2.0, 3, 30, 0.01, 0.02, rng)}};
  EXPECT_TRUE(suiteVerdict({w}).workloads[0].verdict());  // without the bound: A wins
  w.schemes[1].upperBound = true;
  const SuiteVerdict v = suiteVerdict({w});
  const WorkloadResult& r = v.workloads[0];
  EXPECT_FALSE(r.verdict());
  EXPECT_EQ(r.tied, (std::vector<std::string>{"A", "C"}));
  EXPECT_EQ(r.bounded, std::vector<std::string>{"C"});
  EXPECT_GT(r.ratio.at("C").lo, 1.9);
  EXPECT_EQ(v.schemes[0].wins + v.schemes[1].wins, 0);
  EXPECT_EQ(verdictJson(v)["workloads"][0]["tied_at_an_upper_bound"], nlohmann::json::array({"C"}));
}

// From case records: a matched case whose coarsest setting was already under the target (as the
// search writes it: unreachable, achieved below the target) is compared at an upper bound; one
// whose finest setting stayed above the target is missing.
TEST(SuiteVerdict, CaseRecordsMarkAnOverAccurateMatchAsAnUpperBound) {
  RunData run;
  auto add = [&](const std::string& scheme, double ms, nlohmann::json matched) {
    CaseData c;
    c.id = scheme + "_t_flyover_64x36";
    c.status = "ok";
    c.scheme = scheme;
    c.terrain = "t";
    c.path = "flyover.csv";
    c.width = 64;
    c.height = 36;
    c.matched = std::move(matched);
    for (int rep = 0; rep < 3; ++rep)
      for (int f = 0; f < 4; ++f) c.frames.push_back({{"frame", f}, {"gpu_ms", ms * (1.0 + 0.001 * rep)}});
    run.cases[c.id] = c;
  };
  add("A", 1.0, {{"reachable", true}, {"achieved", 0.98}, {"target", 1.0}});
  add("B", 3.0, {{"reachable", false}, {"achieved", 0.4}, {"target", 1.0}, {"param", "tri_size"}, {"value", 64}});
  add("C", 2.0, {{"reachable", false}, {"achieved", 1.5}, {"target", 1.0}, {"param", "tri_size"}, {"value", 0.5}});
  const std::vector<Workload> ws = runWorkloads(run);
  ASSERT_EQ(ws.size(), 1u);
  const SuiteVerdict v = suiteVerdict(ws);
  const WorkloadResult& r = v.workloads[0];
  EXPECT_EQ(r.cheapest, "A");
  EXPECT_EQ(r.bounded, std::vector<std::string>{"B"});
  EXPECT_FALSE(r.verdict());
  ASSERT_EQ(r.missing.count("C"), 1u);
  EXPECT_NE(r.missing.at("C").find("target unreachable"), std::string::npos) << r.missing.at("C");
}

TEST(SuiteVerdict, RefusesRaggedTimings) {
  SchemeTimings a{"A", {{1, 1, 1}, {1, 1}}, ""};
  EXPECT_THROW(suiteVerdict({{"w", {a}}}), std::invalid_argument);
  SchemeTimings b{"B", {{1, 1, 1}}, ""}, c{"C", {{1, 1}}, ""};
  EXPECT_THROW(suiteVerdict({{"w", {b, c}}}), std::invalid_argument);
}

// A real run through the CLI: 3 repetitions on two paths, verdict.json with an interval for every
// scheme on every workload, and the wins and ties adding up.
TEST(SuiteVerdict, VerdictCommandWritesVerdictJsonOfARun) {
  namespace fs = std::filesystem;
  const std::string dir = lb::test::freshDir("verdict");
  fs::create_directories(dir);
  const std::string cfg = dir + "/verdict.json.in";
  nlohmann::json c = lb::test::readJson(lb::test::kTinyConfig);
  c["name"] = "verdict";
  c["repetitions"] = 3;
  c["max_frames"] = 12;
  c["paths"] = {std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv",
                std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/lowalt.csv"};
  std::ofstream(cfg) << c.dump(2);
  const std::string run = dir + "/run";
  lb::test::CliOut r = lb::test::lodbench("run " + cfg + " --out " + run + " -q");
  ASSERT_EQ(r.code, 0) << r.text;
  lb::test::CliOut v = lb::test::lodbench("verdict " + run);
  ASSERT_EQ(v.code, 0) << v.text;
  EXPECT_NE(v.text.find("| uniform |"), std::string::npos) << v.text;
  const nlohmann::json j = lb::test::readJson(run + "/verdict.json");
  ASSERT_EQ(j["workloads"].size(), 2u) << j.dump(2);
  int winsAndTies = 0;
  for (const auto& w : j["workloads"]) {
    EXPECT_TRUE(w["no_interval"].empty());
    for (const char* s : {"uniform", "sphere"}) {
      const auto& r = w["ratio"][s];
      ASSERT_TRUE(r["lo"].is_number()) << w.dump(2);
      EXPECT_LE(r["lo"].get<double>(), r["value"].get<double>());
      EXPECT_GE(r["hi"].get<double>(), r["value"].get<double>());
    }
    EXPECT_EQ(w["ratio"][w["cheapest"].get<std::string>()]["value"], 1.0);
  }
  for (const auto& s : j["schemes"]) {
    EXPECT_EQ(s["workloads"], 2);
    winsAndTies += s["wins"].get<int>() + s["ties"].get<int>();
    EXPECT_TRUE(s["geomean_ratio"]["lo"].is_number());
  }
  EXPECT_GE(winsAndTies, 2) << "every workload has a winner or a tie";
  lb::test::CliOut bad = lb::test::lodbench("verdict " + dir + "/nothing");
  EXPECT_EQ(bad.code, 2) << bad.text;
}

// "interleave": the repetitions run as rounds across the sweep (every case, then every case again),
// each later round with the first round's parameters; each case's record holds every round's frames
// as its repetitions, and the verdict reads them.
TEST(SuiteVerdict, InterleavedRoundsRunEveryCaseOncePerRound) {
  const std::string dir = lb::test::freshDir("interleave");
  std::filesystem::create_directories(dir);
  const std::string cfg = dir + "/interleave.json";
  nlohmann::json c = lb::test::readJson(lb::test::kTinyConfig);
  c["name"] = "interleave";
  c["repetitions"] = 3;
  c["max_frames"] = 6;
  c["interleave"] = true;
  c["paths"] = {std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv"};
  std::ofstream(cfg) << c.dump(2);
  const std::string run = dir + "/run";
  lb::test::CliOut r = lb::test::lodbench("run " + cfg + " --out " + run);
  ASSERT_EQ(r.code, 0) << r.text;
  // Round-major order: both cases' round 2 before either's round 3.
  std::vector<std::string> rounds;
  std::istringstream lines(r.text);
  for (std::string line; std::getline(lines, line);)
    if (line.find("  round ") == 0) rounds.push_back(line.substr(8, 3));
  EXPECT_EQ(rounds, (std::vector<std::string>{"2/3", "2/3", "3/3", "3/3"})) << r.text;
  for (const auto& e : std::filesystem::directory_iterator(run + "/cases")) {
    const nlohmann::json cj = lb::test::readJson(e.path().string());
    ASSERT_EQ(cj["status"], "ok") << cj["reason"];
    EXPECT_EQ(cj["frames"].size(), 18u) << "3 rounds of 6 frames";
    EXPECT_EQ(cj["inputs"]["measurement"]["interleave"], true);
  }
  lb::test::CliOut v = lb::test::lodbench("verdict " + run);
  ASSERT_EQ(v.code, 0) << v.text;
  const nlohmann::json j = lb::test::readJson(run + "/verdict.json");
  EXPECT_TRUE(j["workloads"][0]["no_interval"].empty()) << j.dump(2);
  // The report opens with the verdict, which `report` writes beside it first.
  std::filesystem::remove(run + "/verdict.json");
  lb::test::CliOut rep = lb::test::lodbench("report " + run + " --no-html");
  ASSERT_EQ(rep.code, 0) << rep.text;
  EXPECT_TRUE(std::filesystem::exists(run + "/verdict.json"));
  std::ifstream md(run + "/report/report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), {});
  const size_t verdict = text.find("## Verdict"), context = text.find("## Context");
  ASSERT_NE(verdict, std::string::npos) << text.substr(0, 2000);
  EXPECT_LT(verdict, context) << "the verdict opens the report";
  EXPECT_NE(text.find("By workload: "), std::string::npos);
}

// The controls on lavapipe through a real interleaved run: sphere-copy (sphere under another name)
// ties sphere on every workload (at 99.9 % confidence a false verdict between the twins is a
// 1-in-1000 event), and sphere-twice (every timed frame drawn twice) costs well over sphere. That
// its interval excludes 1 is asserted only where the machine is quiet enough for 3 rounds to
// show it (ctest runs tests side by side on 2 cores: a disturbed round widens the interval, which
// may then reach 1, a tie, never a false win); the method's rates are tested on synthetic data above.
TEST(SuiteVerdict, ControlsTieAndLoseAsTheyMust) {
  const std::string dir = lb::test::freshDir("controls");
  std::filesystem::create_directories(dir);
  nlohmann::json c = {{"name", "controls"},
                      {"resolution", {128, 72}},
                      {"grid", 8},
                      {"fps", 10},
                      {"warmup_frames", 2},
                      {"max_frames", 20},
                      {"repetitions", 3},
                      {"interleave", true},
                      {"terrain", {{"type", "procedural"}, {"size", 129}, {"seed", 2}, {"extent", 1000}}},
                      {"paths",
                       {std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv",
                        std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/lowalt.csv"}},
                      {"schemes", {"sphere", "sphere-copy", "sphere-twice"}},
                      {"images", {{"frames", nlohmann::json::array()}, {"modes", nlohmann::json::array()}}},
                      {"measure", {{"every", 0}}}};
  std::ofstream(dir + "/controls.json") << c.dump(2);
  const std::string run = dir + "/run";
  lb::test::CliOut r = lb::test::lodbench("run " + dir + "/controls.json --out " + run + " -q");
  ASSERT_EQ(r.code, 0) << r.text;
  lb::test::CliOut v = lb::test::lodbench("verdict " + run + " --confidence 0.999");
  ASSERT_EQ(v.code, 0) << v.text;
  const nlohmann::json j = lb::test::readJson(run + "/verdict.json");
  ASSERT_EQ(j["workloads"].size(), 2u);
  for (const auto& w : j["workloads"]) {
    const auto& tied = w["tied"];
    EXPECT_NE(std::find(tied.begin(), tied.end(), "sphere"), tied.end()) << w.dump(2);
    EXPECT_NE(std::find(tied.begin(), tied.end(), "sphere-copy"), tied.end()) << w.dump(2);
    EXPECT_EQ(w["verdict"], "no verdict") << w.dump(2);
    const double copy = w["cost_ms"]["sphere-copy"], sphere = w["cost_ms"]["sphere"];
    // Loose bounds: ctest runs other tests beside this one, and their load lands on some rounds.
    EXPECT_GT(copy / sphere, 0.67) << w.dump(2);
    EXPECT_LT(copy / sphere, 1.5) << w.dump(2);
    const auto& twice = w["ratio"]["sphere-twice"];
    const double cTwice = w["cost_ms"]["sphere-twice"];
    EXPECT_GT(cTwice, 1.15 * std::max(copy, sphere)) << "two draws of a frame cost more than one: " << w.dump(2);
    EXPECT_NE(w["cheapest"], "sphere-twice");
    const double spread = twice["hi"].get<double>() / twice["lo"].get<double>();
    if (spread < 1.5) EXPECT_GT(twice["lo"].get<double>(), 1.0) << w.dump(2);
  }
}
