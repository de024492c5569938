// gbench.json pins Google Benchmark's JSON schema (the fields its compare.py reads) on a hand-made
// run: per-repetition entries, aggregates, counters, and a failed case recorded with its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "error.h"
#include "results/gbench_json.h"
#include "synthetic_run.h"

namespace lb {
namespace {

using test::json;

TEST(GbenchJson, SchemaFieldsRepetitionsAndCounters) {
  json ctx = test::runContext();
  ctx["config"]["repetitions"] = 2;
  // Frames 0..3 twice: repetition 0 has gpu ms 1, 2, 3, 4 (median 2.5), repetition 1 has 5, 6, 7, 8 (6.5).
  json ok = test::caseDoc("uniform-level8", {1, 2, 3, 4, 5, 6, 7, 8});
  for (int i = 0; i < 8; ++i) ok["frames"][i]["frame"] = i % 4;
  ok["summary"] = {
      {"gpu_ms", {{"median", 4.5}}}, {"err_mean_px", {{"mean", 0.75}, {"median", 0.5}}}, {"saturated_fraction", 0.25}};
  json failed = test::caseDoc("sphere-tri3", {}, "failed");
  std::string dir = test::writeRun("gbench", ctx, {ok, failed});
  json g = googleBenchmarkJson(dir);

  const json& c = g["context"];
  for (const char* key : {"date", "host_name", "executable", "num_cpus", "mhz_per_cpu", "cpu_scaling_enabled", "caches",
                          "load_avg", "library_build_type", "device", "driver", "git_commit"})
    EXPECT_TRUE(c.contains(key)) << key;
  EXPECT_EQ(c["date"], "2026-11-21T20:00:00+00:00");
  EXPECT_EQ(c["host_name"], "testhost");
  EXPECT_EQ(c["library_build_type"], "release");
  EXPECT_EQ(c["git_commit"], "abc123");
  EXPECT_TRUE(c["caches"].is_array());
  EXPECT_TRUE(c["load_avg"].is_array());

  const json& b = g["benchmarks"];
  ASSERT_EQ(b.size(), 1u + 5u);  // the failed case (sorted first), 2 repetitions + mean/median/stddev
  EXPECT_EQ(b[0]["name"], "sphere-tri3");
  EXPECT_EQ(b[0]["error_occurred"], true);
  EXPECT_EQ(b[0]["error_message"], "failed: device lost");

  for (int r = 0; r < 2; ++r) {
    const json& e = b[1 + r];
    EXPECT_EQ(e["name"], "uniform-level8");
    EXPECT_EQ(e["run_name"], "uniform-level8");
    EXPECT_EQ(e["run_type"], "iteration");
    EXPECT_EQ(e["family_index"], 1);
    EXPECT_EQ(e["per_family_instance_index"], 0);
    EXPECT_EQ(e["repetitions"], 2);
    EXPECT_EQ(e["repetition_index"], r);
    EXPECT_EQ(e["threads"], 1);
    EXPECT_EQ(e["iterations"], 4);
    EXPECT_EQ(e["time_unit"], "us");  // microseconds: compare.py prints whole units
    EXPECT_DOUBLE_EQ(e["real_time"].get<double>(), r == 0 ? 2500.0 : 6500.0);
    EXPECT_DOUBLE_EQ(e["cpu_time"].get<double>(), r == 0 ? 5000.0 : 13000.0);  // cpu_ms = 2 x gpu_ms
    EXPECT_DOUBLE_EQ(e["fps"].get<double>(), r == 0 ? 400.0 : 1e6 / 6500.0);
    // clip_invocations of record i is 2000 + 2 i: records 0..3 -> median 2003, records 4..7 -> 2011.
    EXPECT_DOUBLE_EQ(e["triangles"].get<double>(), r == 0 ? 2003.0 : 2011.0);
    EXPECT_DOUBLE_EQ(e["patches"].get<double>(), 64.0);
    EXPECT_DOUBLE_EQ(e["err_mean_px"].get<double>(), 0.75);  // the summary's mean over measured frames
    EXPECT_DOUBLE_EQ(e["saturated_fraction"].get<double>(), 0.25);
    EXPECT_FALSE(e.contains("gpu_ms"));
  }
  EXPECT_EQ(b[3]["name"], "uniform-level8_mean");
  EXPECT_EQ(b[3]["run_type"], "aggregate");
  EXPECT_EQ(b[3]["aggregate_name"], "mean");
  EXPECT_DOUBLE_EQ(b[3]["real_time"].get<double>(), 4500.0);
  EXPECT_EQ(b[3]["time_unit"], "us");
  EXPECT_EQ(b[4]["aggregate_name"], "median");
  EXPECT_EQ(b[5]["aggregate_name"], "stddev");
  EXPECT_NEAR(b[5]["real_time"].get<double>(), 1000.0 * std::sqrt(8.0), 1e-9);  // sample stddev of {2.5, 6.5} ms

  std::string file = writeGoogleBenchmarkJson(dir);
  EXPECT_EQ(file, dir + "/gbench.json");
  EXPECT_EQ(json::parse(std::ifstream(file))["benchmarks"].size(), b.size());
}

TEST(GbenchJson, MissingRunIsAnInputError) {
  EXPECT_THROW(googleBenchmarkJson("/nonexistent/run"), InputError);
}

}  // namespace
}  // namespace lb
