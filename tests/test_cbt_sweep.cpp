// cbt and cbt-ts through whole sweeps, as a user runs them: converged and recorded, two repetitions
// and a depth-only timing mode each restored to the same state (equal instances on every frame, or
// "LOD replay diverged"), every measurement pass on the replayed state, images, and a matched search
// whose result the equal-error section of the report shows.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "config/config.h"
#include "report/equal_error.h"
#include "report/run_data.h"
#include "sweep/runner.h"
#include "sweep_run.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

json treeRun(const std::string& name) {
  return {{"name", name},
          {"resolution", {160, 90}},
          {"grid", 16},
          {"fps", 6},
          {"warmup_frames", 2},
          {"repetitions", 2},
          {"timing", {"shaded", "depth"}},
          {"terrain", {{"type", "procedural"}, {"size", 257}, {"seed", 5}, {"extent", 2000}, {"height_scale", 300}}},
          {"paths", {"paths/dive.csv"}},
          {"schemes", {{{"name", "cbt"}, {"params", {{"tri_size", {3, 7}}}}}, {{"name", "cbt-ts"}}}},
          {"measure", {{"every", 4}, {"passes", {"histogram", "error", "image", "cracks", "popping"}}}},
          {"images", {{"frames", {0, -1}}, {"modes", {"shaded", "heatmap", "error", "cracks"}}, {"worst", false}}}};
}

}  // namespace

TEST(CbtSweep, ConvergesReplaysAndMeasuresEveryCase) {
  const fs::path dir = lbtest::runConfig(treeRun("cbt-sweep"), "cbt_sweep");
  int cases = 0;
  for (const auto& e : fs::directory_iterator(dir / "cases")) {
    const json c = json::parse(std::ifstream(e.path()));
    const std::string id = c["case_id"];
    ASSERT_EQ(c["status"], "ok") << id << ": " << c["reason"];
    const json& s = c["summary"];
    EXPECT_TRUE(s["lod_converged"].get<bool>()) << id;
    EXPECT_LE(s["converge_updates"].get<int>(), 2 * s["cbt_depth"].get<int>() + 8) << id;
    EXPECT_EQ(s["converged_state_sha256"].get<std::string>().size(), 64u) << id;
    // Both repetitions start from the snapshot: the same instances on every frame.
    std::map<int, std::vector<uint64_t>> byFrame;
    int measured = 0;
    for (const json& f : c["frames"]) {
      if (f.contains("instances")) byFrame[f["frame"].get<int>()].push_back(f["instances"].get<uint64_t>());
      if (f.contains("err_p95_px") && f["err_p95_px"].is_number()) {
        ++measured;
        EXPECT_EQ(f["cracks_analytic"], 0) << id << " frame " << f["frame"];
        EXPECT_EQ(f["cracks_pixels"], 0) << id << " frame " << f["frame"];
        if (f["frame"].get<int>() > 0) EXPECT_TRUE(f["pop_mean"].is_number()) << id << " frame " << f["frame"];
      }
    }
    EXPECT_GT(measured, 1) << id;
    for (const auto& [frame, counts] : byFrame) {
      ASSERT_EQ(counts.size(), 2u) << id << " frame " << frame;
      EXPECT_EQ(counts[0], counts[1]) << id << " frame " << frame;
    }
    EXPECT_EQ(c["images"].size(), 8u) << id << ": 2 frames x 4 modes";
    ++cases;
  }
  EXPECT_EQ(cases, 3);
  fs::remove_all(dir);
}

// A matched run: the report's equal-error section has one row per scheme, cheapest first, with
// the lavapipe caveat, and its chart's data.
TEST(CbtSweep, EqualErrorSectionListsEveryMatchedScheme) {
  json cfg = treeRun("cbt-equal-error");
  cfg["repetitions"] = 1;
  cfg.erase("timing");
  cfg.erase("images");
  cfg["schemes"] = {"cbt", "cbt-ts", "sphere", "cdlod"};
  cfg["match"] = {{"metric", "err_p95_px"}, {"value", 1.0}, {"frames", 2}, {"iterations", 4}};
  cfg["measure"] = {{"every", 4}, {"passes", {"histogram", "error"}}};
  const fs::path dir = lbtest::runConfig(cfg, "cbt_match");
  const ReportRun run = loadReportRun(dir.string());
  const EqualErrorSection eq = equalErrorSection(run);
  ASSERT_TRUE(eq.present);
  EXPECT_NE(eq.title.find("1"), std::string::npos) << eq.title;
  EXPECT_NE(eq.caveat.find("no verdict on the tessellator"), std::string::npos) << eq.caveat;
  ASSERT_EQ(eq.table.rows.size(), 4u);
  std::set<std::string> schemes;
  double last = 0;
  for (const auto& row : eq.table.rows) {
    schemes.insert(row[0].md);
    const double ms = std::stod(row[5].md);
    EXPECT_GE(ms, last) << "rows are cheapest first";
    last = ms;
  }
  EXPECT_EQ(schemes, (std::set<std::string>{"cbt", "cbt-ts", "sphere", "cdlod"}));
  EXPECT_EQ(eq.chart.section, "equal-error");
  EXPECT_FALSE(eq.chart.data.empty());
  fs::remove_all(dir);
}

// A run without a match has no such section.
TEST(CbtSweep, NoEqualErrorSectionWithoutAMatch) {
  ReportRun run;
  run.context = {{"device", "llvmpipe"}};
  EXPECT_FALSE(equalErrorSection(run).present);
}

// `lodbench render` of a stateful scheme walks the case's history (converge at frame 0, warm up,
// the updates of frames 0 ... f) and so gives the run's own image of frame f byte for byte: cbt
// and cbt-ts, two frames of two paths. Before, it drew the initial four leaves whatever the frame.
TEST(CbtSweep, RenderGivesTheRunsOwnImageOfAStatefulFrame) {
  json cfg = treeRun("cbt-render");
  cfg["repetitions"] = 1;
  cfg.erase("timing");
  cfg["paths"] = {"paths/dive.csv", "paths/flyover.csv"};
  cfg["schemes"] = {{{"name", "cbt"}, {"params", {{"tri_size", 5}}}}, "cbt-ts"};
  cfg["measure"] = {{"every", 0}};
  cfg["images"] = {{"frames", {2, 6}}, {"modes", {"shaded"}}, {"worst", false}, {"resolution", {160, 90}}};
  const fs::path dir = lbtest::runConfig(cfg, "cbt_render");
  int compared = 0;
  std::set<uint64_t> instanceCounts;
  for (const auto& e : fs::directory_iterator(dir / "cases")) {
    const json c = json::parse(std::ifstream(e.path()));
    const std::string id = c["case_id"], scheme = c["scheme"];
    ASSERT_EQ(c["status"], "ok") << id << ": " << c["reason"];
    std::string params;
    for (const auto& [k, v] : c["params"].items()) params += " --param " + k + "=" + v.dump();
    for (int frame : {2, 6}) {
      for (const json& f : c["frames"])
        if (f["frame"] == frame && f.contains("instances")) instanceCounts.insert(f["instances"].get<uint64_t>());
      const fs::path given = c["path"].get<std::string>();
      const fs::path pathFile = given.is_absolute() ? given : fs::path(kConfigs) / given;
      const fs::path mine = dir / ("render_" + id + "_" + std::to_string(frame) + ".png");
      const lb::test::CliOut out = lb::test::lodbench(
          "render --scheme " + scheme + params + " --path " + pathFile.string() + " --frame " + std::to_string(frame) +
              " --fps 6 --width 160 --height 90 --grid 16 --size 257 --seed 5 --extent 2000 --height-scale 300 "
              "--warmup 2 --out " +
              mine.string(),
          false);
      ASSERT_EQ(out.code, 0) << out.text;
      const fs::path theirs = dir / "images" / (id + "_f" + std::to_string(frame) + "_shaded.png");
      ASSERT_TRUE(fs::exists(theirs)) << theirs;
      auto bytes = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
      };
      EXPECT_EQ(bytes(mine), bytes(theirs)) << id << " frame " << frame << ": " << out.text;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 8);
  EXPECT_GT(instanceCounts.size(), 2u) << "the frames must draw different trees, or this proves little";
  fs::remove_all(dir);
}
