// lodbench compare on hand-made runs: case matching, exact checks, the timing rule, accuracy,
// statuses, pooling, and the CLI's exit codes and verdict files.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "compare/compare.h"
#include "compare/run_data.h"
#include "compare/verdict.h"
#include "error.h"
#include "synthetic_run.h"

namespace lb {
namespace {

using test::caseDoc;
using test::gpuTimes;
using test::json;
using test::runContext;
using test::writeRun;

CompareReport compareDirs(const std::string& a, const std::string& b, CompareOptions o = {}) {
  return compareRuns(loadRun(a), loadRun(b), o);
}

const CaseComparison& only(const CompareReport& r) {
  EXPECT_EQ(r.cases.size(), 1u);
  return r.cases.front();
}

TEST(Compare, MatchesCasesByIdAndReportsUnmatched) {
  auto a = writeRun("match_a", runContext(), {caseDoc("a", gpuTimes(20, 1)), caseDoc("b", gpuTimes(20, 1))});
  auto b = writeRun("match_b", runContext(), {caseDoc("b", gpuTimes(20, 1)), caseDoc("c", gpuTimes(20, 1))});
  CompareReport r = compareDirs(a, b);
  EXPECT_EQ(only(r).id, "b");
  EXPECT_EQ(r.onlyInBaseline, std::vector<std::string>{"a"});
  EXPECT_EQ(r.onlyInCandidate, std::vector<std::string>{"c"});
  EXPECT_EQ(r.exitCode(), 0);  // unmatched cases are reported, not failed (a new scheme is no regression)
  EXPECT_NE(verdictMarkdown(r).find("only in the baseline: `a`"), std::string::npos);
}

TEST(Compare, IdenticalRunsAreClean) {
  auto a = writeRun("same_a", runContext(), {caseDoc("x", gpuTimes(30, 1.5))});
  CompareReport r = compareDirs(a, a);
  const CaseComparison& c = only(r);
  EXPECT_TRUE(r.exactChecked);
  EXPECT_TRUE(c.exactChecked);
  EXPECT_FALSE(c.exactDiffers);
  EXPECT_EQ(c.timing.verdict, TimingVerdict::Unchanged);
  EXPECT_DOUBLE_EQ(c.timing.ratio, 1.0);
  EXPECT_DOUBLE_EQ(c.timing.p, 1.0);
  EXPECT_EQ(r.exitCode(), 0);
}

TEST(Compare, CounterChangeNamesCaseFrameAndBothValues) {
  json changed = caseDoc("x", gpuTimes(30, 1));
  changed["frames"][7]["clip_invocations"] = 2000 + 2 * 7 + 1;
  changed["frames"][9]["fragment_invocations"] = 5;
  auto a = writeRun("cnt_a", runContext(), {caseDoc("x", gpuTimes(30, 1))});
  auto b = writeRun("cnt_b", runContext(), {changed});
  CompareReport r = compareDirs(a, b);
  const CaseComparison& c = only(r);
  ASSERT_TRUE(c.exactDiffers);
  EXPECT_EQ(c.exact.frame, 7);
  EXPECT_EQ(c.exact.field, "clip_invocations");
  EXPECT_EQ(c.exact.baseline, "2014");
  EXPECT_EQ(c.exact.candidate, "2015");
  EXPECT_EQ(c.exact.framesDiffering, 2);
  EXPECT_EQ(c.exact.fields, (std::vector<std::string>{"clip_invocations", "fragment_invocations"}));
  EXPECT_EQ(r.exitCode(), 1);
  ASSERT_EQ(c.regressions.size(), 1u);  // timings are identical: the counters alone regress
  EXPECT_NE(c.regressions[0].find("frame 7, clip_invocations 2014 -> 2015"), std::string::npos) << c.regressions[0];
}

TEST(Compare, MeasurementFieldsAreExactWhereBothHaveThem) {
  json a = caseDoc("x", gpuTimes(10, 1)), b = a;
  json hist = json::array({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15});
  a["frames"][4]["hist"] = hist;
  hist[3] = 40;
  b["frames"][4]["hist"] = hist;
  a["frames"][5]["cracks_pixels"] = 0;
  b["frames"][5]["cracks_pixels"] = 3;
  b["frames"][6]["cracks_analytic"] = 2;  // absent in the baseline: not compared
  CompareReport r = compareDirs(writeRun("hist_a", runContext(), {a}), writeRun("hist_b", runContext(), {b}));
  const CaseComparison& c = only(r);
  ASSERT_TRUE(c.exactDiffers);
  EXPECT_EQ(c.exact.frame, 4);
  EXPECT_EQ(c.exact.field, "hist[3]");
  EXPECT_EQ(c.exact.baseline, "4");
  EXPECT_EQ(c.exact.candidate, "40");
  EXPECT_EQ(c.exact.framesDiffering, 2);
  EXPECT_EQ(c.exact.fields, (std::vector<std::string>{"hist", "cracks_pixels"}));
}

TEST(Compare, DifferentFrameSetIsAnExactDifference) {
  CompareReport r = compareDirs(writeRun("fs_a", runContext(), {caseDoc("x", gpuTimes(30, 1))}),
                                writeRun("fs_b", runContext(), {caseDoc("x", gpuTimes(20, 1))}));
  const CaseComparison& c = only(r);
  ASSERT_TRUE(c.exactDiffers);
  EXPECT_EQ(c.exact.field, "frames");
  EXPECT_EQ(c.exact.baseline, "30 frames (0..29)");
  EXPECT_EQ(c.exact.candidate, "20 frames (0..19)");
  EXPECT_EQ(r.exitCode(), 1);
}

TEST(Compare, ExactChecksSkippedWithReasonOnAnotherDriver) {
  json changed = caseDoc("x", gpuTimes(30, 1));
  changed["frames"][3]["patches"] = 1;
  CompareReport r =
      compareDirs(writeRun("drv_a", runContext(), {caseDoc("x", gpuTimes(30, 1))}),
                  writeRun("drv_b", runContext("llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa 24.0"), {changed}));
  EXPECT_FALSE(r.exactChecked);
  EXPECT_NE(r.exactSkipReason.find("context.driver_info differs"), std::string::npos) << r.exactSkipReason;
  EXPECT_FALSE(only(r).exactChecked);
  EXPECT_EQ(r.exitCode(), 0);
  EXPECT_NE(verdictMarkdown(r).find("Skipped: context.driver_info differs"), std::string::npos);
}

// Timing rule: significant (p < alpha) AND ratio > 1 + threshold. 30 frames each side with the
// same 2% spread: a 30% shift separates the samples completely (p ~ 1e-11).
TEST(Compare, TimingRegressionNeedsSignificanceAndThreshold) {
  auto base = writeRun("t_base", runContext(), {caseDoc("x", gpuTimes(30, 1.0))});
  auto slower = writeRun("t_slow", runContext(), {caseDoc("x", gpuTimes(30, 1.3))});
  CompareReport r = compareDirs(base, slower);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Regression);
  EXPECT_NEAR(only(r).timing.ratio, 1.3, 1e-12);
  EXPECT_LT(only(r).timing.p, 1e-6);
  EXPECT_EQ(r.exitCode(), 1);

  // 5% slower: just as significant, but under the 10% threshold.
  auto bit = writeRun("t_bit", runContext(), {caseDoc("x", gpuTimes(30, 1.05))});
  r = compareDirs(base, bit);
  EXPECT_LT(only(r).timing.p, 0.01);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Unchanged);
  EXPECT_EQ(r.exitCode(), 0);
  CompareOptions strict;
  strict.threshold = 0.02;
  EXPECT_EQ(compareDirs(base, bit, strict).exitCode(), 1);

  // Faster: an improvement, exit 0.
  auto faster = writeRun("t_fast", runContext(), {caseDoc("x", gpuTimes(30, 0.7))});
  r = compareDirs(base, faster);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Improvement);
  EXPECT_EQ(r.improvements(), 1);
  EXPECT_EQ(r.exitCode(), 0);
}

// Three frames a side cannot be significant at 0.01: the smallest two-sided p for n1 = n2 = 3 is
// erfc(((9 - 4.5 - 0.5) / sqrt(9 * 7 / 12)) / sqrt 2) = 0.081, so even a 50% slowdown is not flagged.
TEST(Compare, TooFewFramesAreNeverSignificant) {
  CompareReport r = compareDirs(writeRun("few_a", runContext(), {caseDoc("x", {1.0, 1.01, 1.02})}),
                                writeRun("few_b", runContext(), {caseDoc("x", {1.5, 1.51, 1.52})}));
  EXPECT_NEAR(only(r).timing.p, std::erfc(4.0 / std::sqrt(63.0 / 12.0) / std::sqrt(2.0)), 1e-12);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Unchanged);
}

TEST(Compare, AccuracyMayNotGetWorseBeyondTolerance) {
  json a = caseDoc("x", gpuTimes(20, 1)), b = a;
  a["summary"] = {{"err_mean_px", {{"mean", 1.0}}},
                  {"err_p95_px", {{"mean", 3.0}}},
                  {"img_psnr_db", {{"mean", 40.0}}},
                  {"img_ssim", {{"mean", 0.95}}}};
  b["summary"] = {{"err_mean_px", {{"mean", 1.05}}},  // +5% > 2%: worse
                  {"err_p95_px", {{"mean", 2.0}}},    // better
                  {"img_psnr_db", {{"mean", 39.5}}},  // -1.25% within 2%
                  {"img_ssim", nullptr}};             // unavailable: skipped
  CompareReport r = compareDirs(writeRun("acc_a", runContext(), {a}), writeRun("acc_b", runContext(), {b}));
  const CaseComparison& c = only(r);
  ASSERT_EQ(c.accuracy.size(), 3u);
  EXPECT_EQ(c.accuracy[0].metric, "err_mean_px");
  EXPECT_TRUE(c.accuracy[0].worse);
  EXPECT_FALSE(c.accuracy[1].worse);
  EXPECT_FALSE(c.accuracy[2].worse);
  EXPECT_EQ(r.exitCode(), 1);
  CompareOptions lenient;
  lenient.errorTolerance = 0.10;
  EXPECT_EQ(compareDirs(writeRun("acc_a", runContext(), {a}), writeRun("acc_b", runContext(), {b}), lenient).exitCode(),
            0);
}

TEST(Compare, CaseFailingInTheCandidateIsARegression) {
  CompareReport r = compareDirs(writeRun("st_a", runContext(), {caseDoc("x", gpuTimes(20, 1))}),
                                writeRun("st_b", runContext(), {caseDoc("x", {}, "failed")}));
  ASSERT_EQ(only(r).regressions.size(), 1u);
  EXPECT_EQ(only(r).regressions[0], "case failed in the candidate: device lost");
  EXPECT_EQ(r.exitCode(), 1);
  // The other way round it is an improvement.
  r = compareDirs(writeRun("st_b", runContext(), {caseDoc("x", {}, "failed")}),
                  writeRun("st_a", runContext(), {caseDoc("x", gpuTimes(20, 1))}));
  EXPECT_TRUE(only(r).improved);
  EXPECT_EQ(r.exitCode(), 0);
}

TEST(Compare, PoolingConcatenatesRoundsAndKeepsFailures) {
  RunData r1 = loadRun(writeRun("pool_1", runContext(), {caseDoc("x", gpuTimes(10, 1)), caseDoc("y", gpuTimes(5, 1))}));
  RunData r2 = loadRun(writeRun("pool_2", runContext(), {caseDoc("x", gpuTimes(10, 2)), caseDoc("y", {}, "failed")}));
  RunData p = poolRuns({r1, r2});
  EXPECT_EQ(p.cases["x"].gpuMs.size(), 20u);
  EXPECT_EQ(p.cases["x"].rounds, 2);
  EXPECT_DOUBLE_EQ(p.cases["x"].gpuMs[10], 2.0);
  EXPECT_EQ(p.cases["y"].status, "failed");
  EXPECT_EQ(p.cases["y"].reason, "round 2: device lost");
}

RunData pooledRounds(const std::string& name, const std::vector<double>& levels) {
  std::vector<RunData> rounds;
  for (size_t i = 0; i < levels.size(); ++i)
    rounds.push_back(
        loadRun(writeRun(name + std::to_string(i), runContext(), {caseDoc("x", gpuTimes(30, levels[i]))})));
  return poolRuns(rounds);
}

// A/B rounds: the machine slows down (x1.5) for a while, one round earlier on the B side. Pooled
// frames then differ "significantly" (medians 1.26 vs 1.5: x1.19), but pair by pair (A_i, B_i ran
// next to each other) the ratios are 1, 1.5, 1, 1 with median 1: no regression. A real 30%
// slowdown shows in every pair.
TEST(Compare, RoundsMustAgreeWithThePooledFrames) {
  CompareOptions paired;
  paired.pairedRounds = true;
  RunData a = pooledRounds("rounds_a", {1.0, 1.0, 1.5, 1.5});
  CompareReport r = compareRuns(a, pooledRounds("rounds_b", {1.0, 1.5, 1.5, 1.5}), paired);
  const TimingCheck& t = only(r).timing;
  EXPECT_GT(t.ratio, 1.1);
  EXPECT_LT(t.p, 0.01);
  EXPECT_TRUE(t.pairedRounds);
  EXPECT_EQ(t.roundsBaseline, 4);
  EXPECT_DOUBLE_EQ(t.roundRatio, 1.0);
  EXPECT_EQ(t.verdict, TimingVerdict::Unchanged);
  EXPECT_EQ(r.exitCode(), 0);

  r = compareRuns(a, pooledRounds("rounds_c", {1.3, 1.3, 1.95, 1.95}), paired);
  EXPECT_NEAR(only(r).timing.roundRatio, 1.3, 1e-12);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Regression);
  EXPECT_EQ(r.exitCode(), 1);
}

// One baseline run against three candidate rounds (the CI check): one disturbed round (x2.5) does
// not move the median of the round medians; a slowdown in most rounds does.
TEST(Compare, CandidateRoundsOutvoteOneDisturbedRound) {
  RunData base = pooledRounds("ci_base", {1.0});
  CompareOptions ci;
  ci.threshold = 1.0;
  CompareReport r = compareRuns(base, pooledRounds("ci_one_bad", {1.0, 2.5, 1.02}), ci);
  const TimingCheck& t = only(r).timing;
  EXPECT_FALSE(t.pairedRounds);
  EXPECT_EQ(t.roundsBaseline, 1);
  EXPECT_EQ(t.roundsCandidate, 3);
  // Every round has the same 2% spread pattern, so round medians scale with the level: 1.02 / 1.0.
  EXPECT_NEAR(t.roundRatio, 1.02, 1e-12);
  EXPECT_EQ(r.exitCode(), 0);
  EXPECT_EQ(compareRuns(base, pooledRounds("ci_slow", {2.5, 2.4, 1.0}), ci).exitCode(), 1);
}

TEST(Compare, InputErrorsNameTheFile) {
  EXPECT_THROW(loadRun("/nonexistent/run"), InputError);
  auto dir = writeRun("bad_case", runContext(), {caseDoc("x", gpuTimes(5, 1))});
  test::writeText(dir + "/cases/broken.json", "{\"case_id\": ");
  try {
    loadRun(dir);
    FAIL() << "no error for a broken case file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/cases/broken.json: not valid JSON"), std::string::npos) << e.what();
  }
}

struct Out {
  int code = -1;
  std::string text;
};

Out runCli(const std::string& args) {
  Out o;
  FILE* p = popen((std::string(LODBENCH_BINARY) + " " + args + " 2>&1").c_str(), "r");
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), int(buf.size()), p)) o.text += buf.data();
  int status = pclose(p);
  o.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

TEST(CompareCli, ExitCodesAndVerdictFiles) {
  auto base = writeRun("cli_a", runContext(), {caseDoc("x", gpuTimes(30, 1.0))});
  auto slow = writeRun("cli_b", runContext(), {caseDoc("x", gpuTimes(30, 1.3))});
  std::string js = ::testing::TempDir() + "/lodbench_verdict.json", md = ::testing::TempDir() + "/lodbench_verdict.md";
  std::filesystem::remove(js);
  std::filesystem::remove(md);

  Out o = runCli("compare " + base + " " + base);
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("no regression (1 cases)"), std::string::npos) << o.text;

  o = runCli("compare " + base + " " + slow + " --json " + js + " --md " + md);
  EXPECT_EQ(o.code, 1) << o.text;
  EXPECT_NE(o.text.find("REGRESSION in 1 of 1 cases"), std::string::npos) << o.text;
  json v = json::parse(std::ifstream(js));
  EXPECT_EQ(v["verdict"], "regression");
  EXPECT_EQ(v["schema_version"], kVerdictSchemaVersion);
  EXPECT_EQ(v["cases"][0]["timing"]["verdict"], "regression");
  EXPECT_TRUE(std::filesystem::exists(md));
  EXPECT_EQ(runCli("compare " + base + " " + slow + " --threshold 0.5").code, 0);

  o = runCli("compare /nonexistent/base " + base);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("/nonexistent/base: no such run directory"), std::string::npos) << o.text;

  auto broken = writeRun("cli_broken", runContext(), {});
  test::writeText(broken + "/run.json", "not json");
  o = runCli("compare " + base + " " + broken);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(broken + "/run.json: not valid JSON"), std::string::npos) << o.text;

  o = runCli("compare " + base + " " + base + " --json /nonexistent/dir/v.json");
  EXPECT_EQ(o.code, 2) << o.text;  // not 1: exit 1 means a regression
  EXPECT_NE(o.text.find("/nonexistent/dir/v.json"), std::string::npos) << o.text;

  auto wrongType = writeRun("cli_type", runContext(), {caseDoc("x", gpuTimes(5, 1))});
  test::writeText(wrongType + "/cases/y.json", R"({"case_id": "y", "frames": [], "status": 3})");
  o = runCli("compare " + base + " " + wrongType);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(wrongType + "/cases/y.json: "), std::string::npos) << o.text;

  EXPECT_EQ(runCli("compare " + base).code, 2);                              // candidate missing
  EXPECT_EQ(runCli("compare " + base + " " + base + " --alpha 2").code, 2);  // out of range
  for (const char* sub : {"compare", "ab", "gbench"}) EXPECT_EQ(runCli(std::string(sub) + " --help").code, 0) << sub;
}

}  // namespace
}  // namespace lb
