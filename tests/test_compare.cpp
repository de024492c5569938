// lodbench compare on hand-made runs: case matching, exact checks, the timing rule, accuracy,
// statuses, pooling, and the CLI's exit codes and verdict files.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "compare/compare.h"
#include "compare/run_data.h"
#include "compare/significance.h"
#include "compare/verdict.h"
#include "error.h"
#include "render/scheme.h"
#include "schemes/registry.h"
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

// A folder of rounds r1/, r2/, ... of one case "x": round i's frames at levels[i] with the same
// 2% spread pattern, so each round's median is levels[i] * the pattern's median.
std::string writeRounds(const std::string& name, const std::vector<double>& levels,
                        const json& context = runContext()) {
  std::string dir = ::testing::TempDir() + "/lodbench_synthetic/" + name;
  std::filesystem::remove_all(dir);
  for (size_t i = 0; i < levels.size(); ++i) {
    std::string r = writeRun(name + "_tmp", context, {caseDoc("x", gpuTimes(30, levels[i]))});
    std::filesystem::create_directories(dir);
    std::filesystem::rename(r, dir + "/r" + std::to_string(i + 1));
  }
  return dir;
}

RunData rounds(const std::string& name, const std::vector<double>& levels) {
  return poolRuns(loadRounds(writeRounds(name, levels)));
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
  RunData a = rounds("same_a", {1.5, 1.5, 1.5});
  CompareReport r = compareRuns(a, a, {});
  const CaseComparison& c = only(r);
  EXPECT_TRUE(r.exactChecked);
  EXPECT_TRUE(c.exactChecked);
  EXPECT_FALSE(c.exactDiffers);
  EXPECT_EQ(c.timing.verdict, TimingVerdict::Unchanged);
  EXPECT_DOUBLE_EQ(c.timing.ratio, 1.0);
  EXPECT_DOUBLE_EQ(c.timing.p, 1.0);
  EXPECT_EQ(r.exitCode(), 0);
  EXPECT_TRUE(r.notChecked.empty());
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
  b["frames"][6]["cracks_analytic"] = 2;  // absent in the baseline: nothing to compare against
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

// Defect: counters were skipped on another driver and the verdict said "clean". Now
// --require-exact makes it an error, and without the flag the verdict says loudly what it did not check.
TEST(Compare, OtherDriverCountersAreAnErrorWithRequireExactAndLoudWithout) {
  json changed = caseDoc("x", gpuTimes(30, 1));
  changed["frames"][3]["patches"] = 1;
  auto a = writeRun("drv_a", runContext(), {caseDoc("x", gpuTimes(30, 1))});
  auto b = writeRun("drv_b", runContext("llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa 24.0"), {changed});
  CompareOptions exact;
  exact.requireExact = true;
  try {
    compareDirs(a, b, exact);
    FAIL() << "counters that cannot be compared passed --require-exact";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("context.driver_info differs"), std::string::npos) << e.what();
  }
  CompareReport r = compareDirs(a, b);
  EXPECT_FALSE(r.exactChecked);
  EXPECT_FALSE(only(r).exactChecked);
  ASSERT_FALSE(r.notChecked.empty());
  EXPECT_NE(r.notChecked[0].find("NOT checked: context.driver_info differs"), std::string::npos) << r.notChecked[0];
  std::string md = verdictMarkdown(r);
  EXPECT_NE(md.find("## NOT CHECKED"), std::string::npos) << md;
  EXPECT_NE(md.find("**NOT CHECKED**: context.driver_info differs"), std::string::npos) << md;
  EXPECT_EQ(verdictJson(r)["not_checked"].size(), r.notChecked.size());
}

// Defect: a metric in the baseline and missing in the candidate was skipped, so a pass
// that broke (or stopped running) passed the check.
TEST(Compare, MetricMissingInTheCandidateIsARegression) {
  json a = caseDoc("x", gpuTimes(10, 1)), b = a;
  a["summary"] = {{"err_mean_px", {{"mean", 1.0}}}, {"img_ssim", {{"mean", 0.9}}}};
  b["summary"] = {{"err_mean_px", {{"mean", 1.0}}}};  // img_ssim gone
  CompareReport r = compareDirs(writeRun("miss_a", runContext(), {a}), writeRun("miss_b", runContext(), {b}));
  ASSERT_EQ(only(r).regressions.size(), 1u);
  EXPECT_EQ(only(r).regressions[0], "img_ssim present in the baseline, missing in the candidate");
  EXPECT_EQ(r.exitCode(), 1);

  json fa = caseDoc("x", gpuTimes(10, 1)), fb = fa;
  fa["frames"][2]["cracks_pixels"] = 0;  // measured in the baseline, absent in the candidate
  r = compareDirs(writeRun("miss_fa", runContext(), {fa}), writeRun("miss_fb", runContext(), {fb}));
  ASSERT_TRUE(only(r).exactDiffers);
  EXPECT_EQ(only(r).exact.field, "cracks_pixels");
  EXPECT_EQ(only(r).exact.candidate, "\"absent\"");
  EXPECT_EQ(r.exitCode(), 1);
}

// Timing rule: rounds are the samples; significant (p < alpha, Welch on log round medians) AND
// ratio > 1 + threshold. Rounds 1% apart: a 30% shift is t ~ 30 on ~4 degrees of freedom.
TEST(Compare, TimingRegressionNeedsSignificanceAndThreshold) {
  RunData base = rounds("t_base", {1.0, 1.01, 0.99});
  CompareReport r = compareRuns(base, rounds("t_slow", {1.3, 1.313, 1.287}), {});
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Regression);
  EXPECT_NEAR(only(r).timing.ratio, 1.3, 1e-3);
  EXPECT_LT(only(r).timing.p, 1e-4);
  EXPECT_LT(only(r).timing.lo, 1.3);
  EXPECT_GT(only(r).timing.hi, 1.3);
  EXPECT_EQ(r.exitCode(), 1);

  // 5% slower: significant, but under the 10% threshold.
  RunData bit = rounds("t_bit", {1.05, 1.0605, 1.0395});
  r = compareRuns(base, bit, {});
  EXPECT_LT(only(r).timing.p, 0.01);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Unchanged);
  EXPECT_EQ(r.exitCode(), 0);
  CompareOptions strict;
  strict.threshold = 0.02;
  EXPECT_EQ(compareRuns(base, bit, strict).exitCode(), 1);

  // Faster: an improvement, exit 0.
  r = compareRuns(base, rounds("t_fast", {0.7, 0.707, 0.693}), {});
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Improvement);
  EXPECT_EQ(r.improvements(), 1);
  EXPECT_EQ(r.exitCode(), 0);
}

// Defect: frames were judged as independent samples. One round a side whose frames sit
// tightly around different levels (a run that happened to be slower, x1.4) was flagged as a
// regression (pooled-frame p ~ 1e-11). Now one round is no evidence: ratio reported, no verdict.
// With rounds whose levels scatter as runs on a loaded machine do, a 1.2 vs 1.4 difference of
// pooled frames is not significant either.
TEST(Compare, FramesAreNotSamplesNoFalseAlarmFromOneDisturbedRun) {
  CompareReport r = compareDirs(writeRun("fas_a", runContext(), {caseDoc("x", gpuTimes(30, 1.0))}),
                                writeRun("fas_b", runContext(), {caseDoc("x", gpuTimes(30, 1.4))}));
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::NotChecked);
  EXPECT_NEAR(only(r).timing.ratio, 1.4, 1e-12);
  EXPECT_NE(only(r).timing.reason.find("no timing verdict: 1 baseline and 1 candidate round(s)"), std::string::npos)
      << only(r).timing.reason;
  EXPECT_EQ(r.exitCode(), 0);
  ASSERT_EQ(r.notChecked.size(), 1u);
  EXPECT_NE(r.notChecked[0].find("timing was NOT judged for 1 of 1 cases"), std::string::npos) << r.notChecked[0];
  EXPECT_NE(verdictMarkdown(r).find("NO VERDICT"), std::string::npos);

  r = compareRuns(rounds("fas_ra", {1.0, 1.4, 1.2}), rounds("fas_rb", {1.4, 1.2, 1.45}), {});
  EXPECT_GT(mannWhitneyU(loadRounds(writeRounds("fas_ra", {1.0, 1.4, 1.2}))[0].cases["x"].gpuMs,
                         loadRounds(writeRounds("fas_rb", {1.4, 1.2, 1.45}))[0].cases["x"].gpuMs)
                .z,
            0);
  EXPECT_GT(only(r).timing.p, 0.05);
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
                  {"img_ssim", {{"mean", 0.95}}}};
  CompareReport r = compareDirs(writeRun("acc_a", runContext(), {a}), writeRun("acc_b", runContext(), {b}));
  const CaseComparison& c = only(r);
  ASSERT_EQ(c.accuracy.size(), 4u);
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

// A/B rounds: the machine slows down (x1.5) for a while, one round earlier on the B side. Pooled
// frames then differ "significantly", but pair by pair (A_i, B_i ran next to each other) the log
// ratios are 0, log 1.5, 0, 0: t = 1 on 3 degrees of freedom, not significant. A real 30%
// slowdown shows in every pair.
TEST(Compare, PairedRoundsJudgeThePairs) {
  CompareOptions paired;
  paired.pairedRounds = true;
  RunData a = rounds("rounds_a", {1.0, 1.0, 1.5, 1.5});
  CompareReport r = compareRuns(a, rounds("rounds_b", {1.0, 1.5, 1.5, 1.5}), paired);
  const TimingCheck& t = only(r).timing;
  EXPECT_TRUE(t.pairedRounds);
  EXPECT_EQ(t.roundsBaseline, 4);
  EXPECT_NEAR(t.p, studentTwoSidedP(1.0, 3), 1e-9);
  EXPECT_EQ(t.verdict, TimingVerdict::Unchanged);
  EXPECT_EQ(r.exitCode(), 0);

  r = compareRuns(a, rounds("rounds_c", {1.3, 1.3, 1.95, 1.95}), paired);
  EXPECT_NEAR(only(r).timing.ratio, 1.3, 1e-12);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Regression);
  EXPECT_EQ(r.exitCode(), 1);
}

// The CI check: three baseline rounds against three candidate rounds at threshold 1.0. One
// disturbed round (x2.5) is not significant; a slowdown in every round is.
TEST(Compare, OneDisturbedRoundIsNotARegression) {
  RunData base = rounds("ci_base", {1.0, 1.01, 0.99});
  CompareOptions ci;
  ci.threshold = 1.0;
  CompareReport r = compareRuns(base, rounds("ci_one_bad", {1.0, 2.5, 1.02}), ci);
  EXPECT_FALSE(only(r).timing.pairedRounds);
  EXPECT_EQ(only(r).timing.roundsCandidate, 3);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::Unchanged);
  EXPECT_EQ(r.exitCode(), 0);
  EXPECT_EQ(compareRuns(base, rounds("ci_slow", {2.5, 2.4, 2.6}), ci).exitCode(), 1);
  // A one-round baseline gives no timing verdict at all, whatever the candidate's rounds say.
  r = compareRuns(rounds("ci_one", {1.0}), rounds("ci_slow", {2.5, 2.4, 2.6}), ci);
  EXPECT_EQ(only(r).timing.verdict, TimingVerdict::NotChecked);
  EXPECT_EQ(r.exitCode(), 0);
}

// A significant 1.56x slowdown under CI's 2x threshold was called "unchanged". The verdict
// line now leads with the ratio and says it is within the threshold; JSON keeps the enum.
TEST(Compare, SignificantSlowdownUnderTheThresholdIsSaidSo) {
  RunData base = rounds("w_base", {1.0, 1.01, 0.99});
  CompareOptions ci;
  ci.threshold = 1.0;
  CompareReport r = compareRuns(base, rounds("w_slow", {1.56, 1.5756, 1.5444}), ci);
  ASSERT_EQ(only(r).timing.verdict, TimingVerdict::Unchanged);
  ASSERT_LT(only(r).timing.p, ci.alpha);
  EXPECT_EQ(r.exitCode(), 0);
  std::string md = verdictMarkdown(r);
  EXPECT_NE(md.find("# lodbench compare: no regression (1 cases); GPU time ratio 1.56x, p = "), std::string::npos)
      << md;
  EXPECT_NE(md.find(": slower, within the threshold (2x)\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| **1.560x** ["), std::string::npos) << md;
  EXPECT_EQ(md.find("unchanged"), std::string::npos) << md;
  json v = verdictJson(r);
  EXPECT_EQ(v["cases"][0]["timing"]["verdict"], "unchanged");
  EXPECT_EQ(v["cases"][0]["timing"]["verdict_text"], "slower, within the threshold (2x)");
  EXPECT_EQ(v["summary"], verdictLine(r));
  // Not significant: no change claimed either way.
  r = compareRuns(base, rounds("w_same", {1.0, 0.99, 1.01}), ci);
  EXPECT_EQ(timingWords(only(r).timing, ci), "no significant change");
  EXPECT_EQ(timingWords(compareRuns(base, rounds("w_big", {2.5, 2.4, 2.6}), ci).cases[0].timing, ci),
            "REGRESSION: slower beyond the threshold (2x)");
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
  auto base = writeRounds("cli_a", {1.0, 1.01, 0.99});
  auto slow = writeRounds("cli_b", {1.3, 1.313, 1.287});
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

  o = runCli("compare /nonexistent/base " + base + "/r1");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("/nonexistent/base: no such run directory"), std::string::npos) << o.text;

  auto other = writeRounds("cli_other", {1.0, 1.01, 0.99}, runContext("llvmpipe (LLVM 15.0.6, 256 bits)", "Mesa 24.0"));
  o = runCli("compare " + base + " " + other + " --require-exact");
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find("--require-exact: counters cannot be compared: context.driver_info differs"), std::string::npos)
      << o.text;
  o = runCli("compare " + base + " " + other);
  EXPECT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("NOT CHECKED: exact counters"), std::string::npos) << o.text;

  auto broken = writeRun("cli_broken", runContext(), {});
  test::writeText(broken + "/run.json", "not json");
  o = runCli("compare " + base + "/r1 " + broken);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(broken + "/run.json: not valid JSON"), std::string::npos) << o.text;

  o = runCli("compare " + base + " " + base + " --json /nonexistent/dir/v.json");
  EXPECT_EQ(o.code, 2) << o.text;  // not 1: exit 1 means a regression
  EXPECT_NE(o.text.find("/nonexistent/dir/v.json"), std::string::npos) << o.text;

  auto wrongType = writeRun("cli_type", runContext(), {caseDoc("x", gpuTimes(5, 1))});
  test::writeText(wrongType + "/cases/y.json", R"({"case_id": "y", "frames": [], "status": 3})");
  o = runCli("compare " + base + "/r1 " + wrongType);
  EXPECT_EQ(o.code, 2) << o.text;
  EXPECT_NE(o.text.find(wrongType + "/cases/y.json: "), std::string::npos) << o.text;

  EXPECT_EQ(runCli("compare " + base).code, 2);                              // candidate missing
  EXPECT_EQ(runCli("compare " + base + " " + base + " --alpha 2").code, 2);  // out of range
  for (const char* sub : {"compare", "ab", "gbench"}) EXPECT_EQ(runCli(std::string(sub) + " --help").code, 0) << sub;
}

// The CI baseline holds instanced cases (cdlod, cdlod-sse, clipmap, chunked, clusters) and
// GPU-indirect ones (cbt, cbt-ts) beside tessellated ones: compare shows their LOD/draw split
// (medians of both sides, not judged) and gives tessellated cases none. Each case's path is its
// scheme's, from the registry, so a scheme added to the baseline needs no edit here.
TEST(Compare, ShowsTheLodAndDrawSplitOfInstancedCases) {
  const std::string base = std::string(LODBENCH_SOURCE_DIR) + "/results/baseline/ci/";
  CompareReport r = compareRuns(loadRun(base + "r1"), loadRun(base + "r2"), CompareOptions{});
  int instanced = 0, indirect = 0;
  for (const CaseComparison& c : r.cases) {
    // The mesh twins are skipped cases on lavapipe (no VK_EXT_mesh_shader): no timings to split.
    if (c.baselineStatus == "skipped") {
      EXPECT_TRUE(c.split.empty()) << c.id;
      continue;
    }
    const Scheme* scheme = findScheme(c.id.substr(0, c.id.find('_')));
    ASSERT_NE(scheme, nullptr) << c.id;
    const DrawPath path = scheme->info().path;
    if (path == DrawPath::GpuIndirect) {  // the compute passes and the draw, no CPU selection
      ++indirect;
      ASSERT_EQ(c.split.size(), 2u) << c.id;
      EXPECT_EQ(c.split[0].key, "lod_ms");
      EXPECT_EQ(c.split[1].key, "draw_ms");
      EXPECT_GT(c.split[0].baseline, 0.0) << c.id;
      continue;
    }
    if (path != DrawPath::InstancedGrid) {
      EXPECT_TRUE(c.split.empty()) << c.id;
      continue;
    }
    ++instanced;
    ASSERT_EQ(c.split.size(), 3u) << c.id;
    EXPECT_EQ(c.split[0].key, "lod_ms");
    EXPECT_EQ(c.split[2].key, "lod_cpu_ms");
    EXPECT_GT(c.split[2].baseline, 0.0) << c.id;
  }
  EXPECT_GE(instanced, 5);  // cdlod, cdlod-sse, clipmap, chunked, clusters
  EXPECT_GE(indirect, 2);   // cbt, cbt-ts
  EXPECT_NE(verdictMarkdown(r).find("## LOD and draw"), std::string::npos);
  EXPECT_TRUE(verdictJson(r)["cases"][0].is_object());
}

}  // namespace
}  // namespace lb
