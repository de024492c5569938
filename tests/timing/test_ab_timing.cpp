// A/B mode on lavapipe, timed: no false alarm when both sides are the same binary (A/A control),
// and a planted 20% GPU slowdown is flagged. ctest runs this binary alone (RUN_SERIAL): other
// tests on the same cores are exactly the noise these tests must not measure.
#include <gtest/gtest.h>

#include <cstdio>

#include "cli_run.h"

namespace lb::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void printTimings(const json& verdict) {
  for (auto& c : verdict["cases"]) {
    const json& t = c["timing"];
    if (!t.contains("p")) continue;  // no verdict: no interval either
    std::printf("    %s: %.3f -> %.3f ms, x%.3f [%.3f, %.3f], p = %.2g, %d pairs: %s\n",
                c["case_id"].get<std::string>().c_str(), t["baseline_ms"].get<double>(),
                t["candidate_ms"].get<double>(), t["ratio"].get<double>(), t["ci_lo"].get<double>(),
                t["ci_hi"].get<double>(), t["p"].get<double>(), t.value("rounds_baseline", 0),
                t["verdict"].get<std::string>().c_str());
  }
}

// A/A control: the same binary on both sides, 6 interleaved rounds, default threshold and alpha.
// (A false alarm needs the 6 round pairs' log ratios to be significant at 0.01 and >10% slower.)
// Even on an idle machine a burst of outside noise can land on one side's rounds: CI saw one
// false 1.109x (p = 0.0017) in many runs. One alarm is therefore answered by a second, independent
// A/A run, which must be clean: two alarms in a row at this alpha mean the protocol, not the luck,
// is wrong. Every other assertion holds for both runs.
json runAa(const std::string& name) {
  std::string out = freshDir(name);
  CliOut o = lodbench(std::string("ab --baseline ") + LODBENCH_BINARY + " --candidate " + LODBENCH_BINARY + " " +
                      kTinyConfig + " --rounds 6 --out " + out);
  json v = readJson(out + "/compare.json");
  printTimings(v);
  EXPECT_EQ(o.code == 0, v["verdict"] == "clean") << o.text;  // the exit status says what the verdict says
  EXPECT_EQ(v["exact"]["checked"], true);
  EXPECT_EQ(v["cases"].size(), 2u);
  for (auto& c : v["cases"]) {
    EXPECT_EQ(c["exact"]["differs"], false) << c["case_id"];  // deterministic counters across processes
    EXPECT_EQ(c["timing"]["n_baseline"], 6 * 60);             // 6 rounds x 30 frames x 2 repetitions
    EXPECT_EQ(c["timing"]["rounds_candidate"], 6);
    EXPECT_EQ(c["timing"]["paired_rounds"], true);
  }
  for (const char* d : {"a1", "b1", "a6", "b6", "compare.md"}) EXPECT_TRUE(fs::exists(out + "/" + d)) << d;
  return v;
}

TEST(AbTiming, SameBinaryOnBothSidesRaisesNoFalseAlarm) {
  json v = runAa("aa");
  if (v["verdict"] != "clean") {
    std::printf("    A/A run 1 gave \"%s\": answered by a second, independent A/A run\n",
                v["verdict"].get<std::string>().c_str());
    v = runAa("aa2");
  }
  EXPECT_EQ(v["verdict"], "clean");
}

// A planted 20% slowdown (run --test-slowdown 0.2) through a wrapper script as binary B.
TEST(AbTiming, PlantedSlowdownIsFlagged) {
#ifdef __SANITIZE_ADDRESS__
  // Under ASan every frame carries a large fixed overhead (x3-5 here) that dilutes the planted 20%
  // below the threshold: a timing claim about the sanitizer build would be about the sanitizer.
  GTEST_SKIP() << "timings of a sanitizer build are not representative";
#endif
  std::string out = freshDir("slow"), wrapper = freshDir("slow.sh");
  std::ofstream(wrapper) << "#!/bin/sh\nexec " << LODBENCH_BINARY << " \"$@\" --test-slowdown 0.2\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  // Rounds are the samples (a paired t-test on 6 pairs: 5 degrees of freedom). This test asks
  // for power, not for the false-alarm rate (the A/A test above and scripts/aa-experiment.sh
  // keep the default 0.01), so it judges at 0.05: on a loaded machine a planted 20% with 4 pairs
  // measured p = 0.04.
  CliOut o = lodbench(std::string("ab --baseline ") + LODBENCH_BINARY + " --candidate " + wrapper + " " + kTinyConfig +
                      " --rounds 6 --alpha 0.05 --out " + out);
  json v = readJson(out + "/compare.json");
  printTimings(v);
  EXPECT_NE(o.text.find("planted test slowdown of 0.2"), std::string::npos) << o.text;
  for (auto& c : v["cases"])
    EXPECT_EQ(c["exact"]["differs"], false) << c["case_id"];  // the extra draws are outside the statistics query
  // Where round-to-round noise (other jobs on the cores) makes the interval wider than x1.5 end
  // to end, no honest test resolves 20% with 6 rounds: that is reported as inconclusive, loudly,
  // with the widths, rather than passed or failed on noise.
  if (v["verdict"] != "regression") {
    std::string widths;
    bool resolvable = false;
    for (auto& c : v["cases"]) {
      const json& t = c["timing"];
      double w = t.contains("ci_hi") ? t["ci_hi"].get<double>() / t["ci_lo"].get<double>() : 1e9;
      widths += " " + c["case_id"].get<std::string>() + ": hi/lo x" + std::to_string(w);
      resolvable = resolvable || w < 1.5;
    }
    if (!resolvable) GTEST_SKIP() << "INCONCLUSIVE: the machine is too noisy to resolve a 20% slowdown:" << widths;
  }
  EXPECT_EQ(o.code, 1) << o.text;
  EXPECT_EQ(v["verdict"], "regression");
  for (auto& c : v["cases"]) EXPECT_GT(c["timing"]["ratio"].get<double>(), 1.0) << c["case_id"];
}

}  // namespace
}  // namespace lb::test
