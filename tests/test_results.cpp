// End-to-end: a tiny sweep writes the documented files; failures are data; reruns resume.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "compare/run_data.h"
#include "config/config.h"
#include "error.h"
#include "report/run_data.h"
#include "results/gbench_json.h"
#include "results/write.h"
#include "sweep/merge.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

static json readJson(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

static Config tinyConfig(const std::string& extraTerrain = "") {
  std::string text = R"({
    "name": "tiny", "resolution": [64, 48], "grid": 8, "fps": 10, "warmup_frames": 1, "max_frames": 4,
    "terrains": [{"type": "procedural", "size": 65, "seed": 3})" +
                     extraTerrain + R"(],
    "paths": ["paths/flyover.csv"],
    "schemes": [{"name": "uniform", "params": {"level": 3}}, "sphere"],
    "images": {"frames": [1], "modes": ["shaded", "heatmap"]}
  })";
  return parseConfig(text, "tiny.json", std::string(LODBENCH_SOURCE_DIR) + "/configs");
}

static fs::path freshDir(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  return d;
}

TEST(Results, SchemaOfEveryFile) {
  fs::path dir = freshDir("lodbench_schema");
  RunTotals t = runSweep(tinyConfig(), {dir.string(), false, false});
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.failed, 0);
  EXPECT_EQ(t.validationErrors, 0);

  json run = readJson(dir / "run.json");
  EXPECT_EQ(run["schema_version"], 1);
  for (const char* key : {"tool_version", "git_commit", "device", "driver", "api_version", "timestamp_period_ns",
                          "config", "host", "time", "build_type"})
    EXPECT_TRUE(run["context"].contains(key)) << key;
  EXPECT_EQ(run["context"]["config"]["name"], "tiny");
  EXPECT_TRUE(run.contains("end_time"));
  EXPECT_EQ(run["totals"]["ok"], 2);

  json c = readJson(dir / "cases" / "uniform-level3_proc65s3_flyover_64x48.json");
  EXPECT_EQ(c["schema_version"], 1);
  EXPECT_EQ(c["status"], "ok");
  EXPECT_EQ(c["params"]["level"], 3.0);
  // A generated terrain records its size and seed, and the samples it ran on.
  EXPECT_EQ(c["terrain"]["size"], 65);
  EXPECT_EQ(c["terrain"]["seed"], 3);
  EXPECT_EQ(c["terrain"]["samples"], json({65, 65}));
  ASSERT_EQ(c["frames"].size(), 4u);
  for (auto& f : c["frames"]) {
    for (const char* key : {"frame", "gpu_ms", "cpu_ms", "fps", "patches", "tes_invocations", "clip_invocations",
                            "clip_primitives", "fragment_invocations"})
      EXPECT_TRUE(f.contains(key)) << key;
    EXPECT_EQ(f["patches"], 64);
    EXPECT_EQ(f["tes_invocations"], 64 * 16);   // (3+1)^2 per patch
    EXPECT_EQ(f["clip_invocations"], 64 * 18);  // 2 * 3^2 per patch
    EXPECT_GT(f["gpu_ms"].get<double>(), 0.0);
  }
  for (int i = 0; i < 4; ++i) EXPECT_EQ(c["frames"][i]["frame"], i) << "frames in order";
  for (const char* key : {"median", "p5", "p95", "p99", "mean"}) EXPECT_TRUE(c["summary"]["gpu_ms"].contains(key));
  EXPECT_EQ(c["summary"]["triangles"]["median"], 64 * 18);
  EXPECT_GT(c["summary"]["fps_median"].get<double>(), 0.0);
  ASSERT_EQ(c["images"].size(), 2u);
  for (auto& img : c["images"]) EXPECT_TRUE(fs::exists(dir / img.get<std::string>())) << img;

  json s = readJson(dir / "summary.json");
  EXPECT_EQ(s["schema_version"], 1);
  EXPECT_EQ(s["cases"].size(), 2u);

  std::ifstream csv(dir / "frames.csv");
  std::string line;
  int rows = 0;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("case_id,frame,gpu_ms", 0), 0u);
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 8);
  for (auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "leftover temp file " << e.path();
}

TEST(Results, FailingCaseIsRecordedAndSweepGoesOn) {
  fs::path dir = freshDir("lodbench_fail");
  fs::create_directories(dir);
  // The config reads its heightmaps (a bad one is exit 2 before any case), so the file breaks
  // after the config was read: its cases fail at run time.
  std::ofstream(dir / "broken.hgt", std::ios::binary) << std::string(8, '\0');
  Config config =
      tinyConfig(R"(, {"type": "r16", "width": 2, "height": 2, "file": ")" + (dir / "broken.hgt").string() + R"("})");
  std::ofstream(dir / "broken.hgt") << "not a heightmap";
  RunTotals t = runSweep(config, {(dir / "run").string(), false, false});
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.failed, 2);
  json s = readJson(dir / "run" / "summary.json");
  int failed = 0;
  for (auto& c : s["cases"])
    if (c["status"] == "failed") {
      ++failed;
      EXPECT_NE(c["reason"].get<std::string>().find("broken.hgt"), std::string::npos) << c["reason"];
    }
  EXPECT_EQ(failed, 2);
  for (auto& e : fs::directory_iterator(dir / "run" / "cases")) {
    const json t = readJson(e.path())["terrain"];
    if (t["type"] != "r16") continue;
    EXPECT_TRUE(t["samples"].is_null()) << "never loaded";
    EXPECT_FALSE(t.contains("size")) << t.dump();
    EXPECT_FALSE(t.contains("seed")) << t.dump();
  }
}

// A file terrain's record carries no size or seed (it uses neither), and names
// the grid of samples it ran on; its identity (inputs, digest) never held them.
TEST(Results, FileTerrainRecordsItsSamplesNotSizeOrSeed) {
  fs::path dir = freshDir("lodbench_file_terrain");
  fs::create_directories(dir);
  std::string bytes;
  for (uint16_t v : {1, 2, 3, 4, 5, 6}) bytes += char(v & 0xff), bytes += char(v >> 8);
  std::ofstream(dir / "t.r16", std::ios::binary) << bytes;
  Config config =
      tinyConfig(R"(, {"type": "r16", "width": 3, "height": 2, "file": ")" + (dir / "t.r16").string() + R"("})");
  std::vector<Case> cases = expandCases(config);
  ASSERT_EQ(cases.size(), 4u);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.id);
    const Heightfield hf = makeHeightfield(c.terrain);
    CaseResult r;
    r.terrainSource = hf.source;
    r.terrainWidth = hf.width;
    r.terrainHeight = hf.height;
    const json t = caseJson(c, r)["terrain"];
    const bool file = c.terrain.type == "r16";
    EXPECT_EQ(t.contains("size"), !file) << t.dump();
    EXPECT_EQ(t.contains("seed"), !file) << t.dump();
    EXPECT_EQ(c.inputs["terrain"].contains("size"), !file) << "identity as before";
    EXPECT_EQ(t["samples"], file ? json({3, 2}) : json({65, 65}));
    if (file) EXPECT_EQ(t["source"]["raster_size"], json({3, 2}));
  }
}

TEST(Results, RerunResumesFinishedCases) {
  fs::path dir = freshDir("lodbench_resume");
  runSweep(tinyConfig(), {dir.string(), false, false});
  auto stamp = fs::last_write_time(dir / "cases" / "sphere_proc65s3_flyover_64x48.json");
  fs::remove(dir / "cases" / "uniform-level3_proc65s3_flyover_64x48.json");  // as if killed before it finished
  RunTotals t = runSweep(tinyConfig(), {dir.string(), false, false});
  EXPECT_EQ(t.resumed, 1);
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(fs::last_write_time(dir / "cases" / "sphere_proc65s3_flyover_64x48.json"), stamp) << "kept, not redone";
  EXPECT_TRUE(fs::exists(dir / "cases" / "uniform-level3_proc65s3_flyover_64x48.json"));
  EXPECT_EQ(readJson(dir / "summary.json")["cases"].size(), 2u);
}

// Measurement passes run after the timing frames: the timing frames' counters are identical
// with measurements on and off, and each measured frame's histogram adds up to its triangles.
TEST(Results, MeasurementsLandInRecordsAndLeaveTimingFramesAlone) {
  Config off = tinyConfig();
  Config on = tinyConfig();
  on.measure.every = 2;
  on.images.modes = {"error", "cracks"};
  fs::path dOff = freshDir("lodbench_measure_off"), dOn = freshDir("lodbench_measure_on");
  EXPECT_EQ(runSweep(off, {dOff.string(), false, false}).ok, 2);
  RunTotals t = runSweep(on, {dOn.string(), false, false});
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.validationErrors, 0);
  for (const char* id : {"uniform-level3_proc65s3_flyover_64x48", "sphere_proc65s3_flyover_64x48"}) {
    SCOPED_TRACE(id);
    json a = readJson(dOff / "cases" / (std::string(id) + ".json"));
    json b = readJson(dOn / "cases" / (std::string(id) + ".json"));
    ASSERT_EQ(a["frames"].size(), b["frames"].size());
    for (size_t i = 0; i < a["frames"].size(); ++i)
      for (const char* k :
           {"patches", "tes_invocations", "clip_invocations", "clip_primitives", "fragment_invocations"})
        EXPECT_EQ(a["frames"][i][k], b["frames"][i][k]) << "frame " << i << " " << k;
    int measured = 0;
    for (auto& f : b["frames"]) {
      if (!f.contains("hist")) continue;
      ++measured;
      uint64_t total = f["hist_offscreen"].get<uint64_t>() + f["hist_backfacing"].get<uint64_t>();
      for (auto& bin : f["hist"]) total += bin.get<uint64_t>();
      EXPECT_EQ(total, f["clip_invocations"].get<uint64_t>()) << "frame " << f["frame"];
      for (const char* k : {"err_mean_px", "err_p95_px", "img_psnr_db", "img_ssim", "cracks_analytic", "cracks_pixels",
                            "pop_mean", "surplus", "tri_area_mean"})
        EXPECT_TRUE(f.contains(k)) << k;
      EXPECT_EQ(f["cracks_analytic"], 0.0);
      EXPECT_EQ(f["cracks_pixels"], 0.0);
    }
    EXPECT_EQ(measured, 2);  // frames 0 and 2 of 4
    EXPECT_EQ(b["summary"]["measured_frames"], 2);
    EXPECT_TRUE(b["summary"].contains("err_mean_px"));
    EXPECT_EQ(b["summary"]["hist_total"].size(), 15u);
    std::set<int> imaged = {1};  // the configured frame and the worst measured frames
    for (auto& [metric, f] : b["summary"]["worst_frames"].items()) imaged.insert(f.get<int>());
    EXPECT_EQ(b["images"].size(), 2 * imaged.size());
    for (auto& img : b["images"]) EXPECT_TRUE(fs::exists(dOn / img.get<std::string>())) << img;
  }
  std::ifstream csv(dOn / "frames.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",hist_14,"), std::string::npos);
  EXPECT_NE(header.find(",err_p95_px,"), std::string::npos);
  EXPECT_NE(header.find(",surplus,"), std::string::npos);
}

// Defect: a device without geometry shaders cannot run the histogram pass, which
// used to mark the whole case skipped and throw its valid timing frames away. Now the pass is null
// with its reason in each measured frame record, and the case keeps its timings and stays ok.
TEST(Results, OptionalPassTheDeviceCannotRunIsNullAndTheCaseStaysOk) {
  Config c = tinyConfig();
  c.measure.every = 2;
  c.measure.passes = {"histogram", "cracks"};
  fs::path d = freshDir("lodbench_skip");
  setenv("LODBENCH_TEST_DISABLE", "geometryShader", 1);
  RunTotals t = runSweep(c, {d.string(), false, false});
  unsetenv("LODBENCH_TEST_DISABLE");
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.skipped, 0);
  EXPECT_EQ(t.failed, 0);
  EXPECT_EQ(t.validationErrors, 0);
  EXPECT_EQ(readJson(d / "run.json")["test_disabled_features"], "geometryShader");
  for (auto& e : fs::directory_iterator(d / "cases")) {
    json k = readJson(e.path());
    SCOPED_TRACE(e.path().string());
    EXPECT_EQ(k["status"], "ok");
    ASSERT_EQ(k["frames"].size(), 4u);  // every timing frame kept
    int measured = 0;
    for (auto& f : k["frames"]) {
      EXPECT_GT(f["clip_invocations"].get<uint64_t>(), 0u);
      if (!f.contains("unavailable")) continue;
      ++measured;
      EXPECT_TRUE(f["hist"].is_null());
      EXPECT_TRUE(f["tri_area_mean"].is_null());
      EXPECT_NE(f["unavailable"]["histogram"].get<std::string>().find("geometryShader"), std::string::npos);
      EXPECT_TRUE(f["cracks_analytic"].is_number());  // the passes the device can run still ran
    }
    EXPECT_EQ(measured, 2);
    EXPECT_TRUE(k["summary"]["hist_total"].is_null());
    EXPECT_NE(k["summary"]["unavailable"]["histogram"].get<std::string>().find("geometryShader"), std::string::npos);
    EXPECT_TRUE(k["summary"]["gpu_ms"].is_object());
  }
}

// Defect: five readers parsed the run directory with five error policies, and the
// aggregates silently dropped an unreadable case file. Now every reader goes through
// results/run_dir.h: an unreadable case file is an error naming it, for report, compare, gbench,
// merge and the aggregates alike.
TEST(Results, EveryReaderNamesAnUnreadableCaseFile) {
  fs::path d = freshDir("lodbench_unreadable");
  fs::create_directories(d / "cases");
  std::ofstream(d / "run.json") << R"({"schema_version": 1, "context": {"tool": "lodbench", "config": {}}})";
  std::ofstream(d / "summary.json") << R"({"schema_version": 1, "context": {}, "cases": []})";
  std::ofstream(d / "cases/good.json") << R"({"case_id": "good", "status": "ok", "frames": []})";
  std::ofstream(d / "cases/bad.json") << R"({"case_id": "bad", "frames": [)";
  const std::string bad = (d / "cases/bad.json").string() + ": not valid JSON";
  auto expectNamed = [&](const char* who, const std::function<void()>& f) {
    try {
      f();
      ADD_FAILURE() << who << " read past an unreadable case file";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << who << ": " << e.what();
    }
  };
  expectNamed("report", [&] { loadReportRun(d.string()); });
  expectNamed("compare", [&] { loadRun(d.string()); });
  expectNamed("gbench", [&] { googleBenchmarkJson(d.string()); });
  expectNamed("aggregates", [&] { writeAggregates(d.string(), json::object()); });
  expectNamed("merge", [&] { mergeRuns((d / "merged").string(), {d.string()}, false); });
}
