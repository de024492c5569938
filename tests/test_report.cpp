// lodbench report on the committed fixture run (tests/data/report_run): the Markdown tables, the
// Vega-Lite specs and their data, the Pareto fronts, and graceful degradation without metrics.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "error.h"
#include "report/charts.h"
#include "report/pareto.h"
#include "report/report.h"
#include "report/run_data.h"
#include "report_fixture.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace lb::test;

std::string tableRow(const std::string& md, const std::string& start) {
  size_t at = md.find("\n" + start);
  return at == std::string::npos ? "" : md.substr(at + 1, md.find('\n', at + 1) - at - 1);
}

// Strips every measurement metric: what a run without measurement passes writes.
void dropMetrics(const fs::path& run) {
  const std::set<std::string> timing = {"frames",    "gpu_ms",  "cpu_ms",          "fps_median",          "fps_mean",
                                        "triangles", "patches", "tes_invocations", "fragment_invocations"};
  auto strip = [&](json& summary) {
    for (auto it = summary.begin(); it != summary.end();)
      it = timing.count(it.key()) ? std::next(it) : summary.erase(it);
  };
  json s = readJson(run / "summary.json");
  for (auto& c : s["cases"]) strip(c["summary"]);
  std::ofstream(run / "summary.json") << s.dump();
  for (auto& e : fs::directory_iterator(run / "cases")) {
    json c = readJson(e.path());
    strip(c["summary"]);
    for (auto& f : c["frames"])
      for (auto it = f.begin(); it != f.end();)
        it = (it.key().rfind("hist", 0) == 0 || it.key().rfind("err_", 0) == 0 || it.key().rfind("tri_", 0) == 0)
                 ? f.erase(it)
                 : std::next(it);
    std::ofstream(e.path()) << c.dump();
  }
}

}  // namespace

TEST(ReportPareto, FrontKeepsExactlyTheUndominatedPoints) {
  // (1,9) (2,5) (3,6) (4,2) (5,2) (2,5): (3,6) is beaten by (2,5); (5,2) by (4,2); the duplicate stays.
  std::vector<double> x{1, 2, 3, 4, 5, 2}, y{9, 5, 6, 2, 2, 5};
  EXPECT_EQ(paretoFront(x, y), (std::vector<size_t>{0, 1, 5, 3}));
  EXPECT_EQ(paretoFront({}, {}), std::vector<size_t>{});
  EXPECT_EQ(paretoFront({3}, {1}), std::vector<size_t>{0});
}

TEST(ReportRun, LoadsFixtureInConfigOrderWithImages) {
  ReportRun run = loadReportRun(kFixture.string());
  json summary = readJson(kFixture / "summary.json");
  ASSERT_EQ(run.cases.size(), summary["cases"].size());
  EXPECT_EQ(run.name, "report_fixture");
  EXPECT_EQ(run.schemes, (std::vector<std::string>{"uniform", "sphere", "phong", "interlock"}));  // config order
  EXPECT_EQ(run.scenarios, (std::vector<std::string>{"flyover", "lowalt"}));
  EXPECT_EQ(run.cases.front().id, "uniform-level4_proc129s1_flyover_96x54");  // level=4 before level=16
  EXPECT_EQ(run.paramLabels,
            (std::vector<std::string>{"level=4", "level=16", "tri_size=2", "tri_size=4", "tri_size=8"}));
  // Images: exactly the PNGs in the fixture's images/ folder, parsed back to case, frame and mode.
  size_t pngs = 0, indexed = 0;
  for (auto& e : fs::directory_iterator(kFixture / "images")) pngs += e.path().extension() == ".png";
  for (auto& [id, frames] : run.images)
    for (auto& [frame, modes] : frames) indexed += modes.size();
  EXPECT_EQ(indexed, pngs);
  EXPECT_EQ(run.images.at("phong-tri_size4_proc129s1_lowalt_96x54").at(6).at("shaded"),
            "images/phong-tri_size4_proc129s1_lowalt_96x54_f6_shaded.png");
  EXPECT_THROW(loadReportRun((kFixture / "cases").string()), InputError);
}

TEST(ReportWrite, MarkdownHasContextStabilityProblemsAndEveryCase) {
  fs::path run = copyFixture("lodbench_report_md");
  ReportOutput out = writeNoHtml(run);
  EXPECT_EQ(out.dir, (run / "report").string());
  EXPECT_EQ(out.charts, 7);  // speed x2, parameter scale study, histogram, timelines x3
  // The fixture predates coverage (docs/results-format.md): its timeline is left out with a note.
  EXPECT_EQ(out.omittedCharts, 1);
  std::string md = readText(run / "report/report.md");

  EXPECT_EQ(tableRow(md, "| device |"), "| device | llvmpipe (LLVM 15.0.6, 256 bits) (vendor 65541, device 0) |");
  EXPECT_EQ(tableRow(md, "| cases |"), "| cases | 14 (11 ok, 1 failed, 2 skipped) |");

  // Stability, phong on lowalt: one ok case (tri_size=4), one failed; cracks are the maxima over its frames.
  json phong = readJson(run / "cases/phong-tri_size4_proc129s1_lowalt_96x54.json");
  double edges = 0, pixels = 0;
  for (auto& f : phong["frames"])
    if (f.contains("cracks_analytic")) {
      edges = std::max(edges, f["cracks_analytic"].get<double>());
      pixels = std::max(pixels, f["cracks_pixels"].get<double>());
    }
  ASSERT_GT(pixels, 0);
  int worst = phong["summary"]["worst_frames"]["cracks_pixels"];
  std::string row = tableRow(md, "| phong | lowalt |");
  EXPECT_EQ(row.rfind("| phong | lowalt | 1 / 1 / 0 | " + formatValue(edges) + " | " + formatValue(pixels) + " |", 0),
            0u)
      << row;
  // The worst cracks frame links to its image (no cracks image in the fixture: the shaded one).
  EXPECT_NE(row.find("[cracks: phong tri_size=4 f" + std::to_string(worst) +
                     "](../images/phong-tri_size4_proc129s1_lowalt_96x54_f" + std::to_string(worst) + "_shaded.png)"),
            std::string::npos)
      << row;
  EXPECT_EQ(tableRow(md, "| interlock | flyover |"), "| interlock | flyover | 0 / 0 / 1 | – | – | – | – | – | – | – |");

  EXPECT_NE(md.find("| `phong-tri_size8_proc129s1_lowalt_96x54` | phong | tri_size=8 | lowalt | failed | "
                    "vkQueueSubmit: VK_ERROR_DEVICE_LOST at frame 5 |"),
            std::string::npos);
  EXPECT_NE(md.find("| `interlock_proc129s1_lowalt_96x54` | interlock | defaults | lowalt | skipped | quad12 patches"),
            std::string::npos);

  // Every case has a row; the timing-only case shows its timings and dashes for its metrics.
  json summary = readJson(run / "summary.json");  // a named object: the loop below refers into it
  for (auto& c : summary["cases"])
    EXPECT_NE(md.find("| `" + c["case_id"].get<std::string>() + "` | "), std::string::npos) << c["case_id"];
  json timingOnly = readJson(run / "cases/sphere-tri_size8_proc129s1_lowalt_96x54.json")["summary"];
  row = tableRow(md, "| `sphere-tri_size8_proc129s1_lowalt_96x54` | sphere | tri_size=8 | lowalt | ok | 8 | " +
                         formatValue(timingOnly["gpu_ms"]["median"].get<double>()) + " |");
  EXPECT_FALSE(row.empty());
  EXPECT_NE(row.find("| – | – |"), std::string::npos) << row;
  EXPECT_NE(md.find("Not shown (no error metrics): sphere tri_size=8 (lowalt)."), std::string::npos);
  EXPECT_NE(md.find("![GPU time vs screen-space error](svg/speed_gpu_ms.svg)"), std::string::npos);
}

TEST(ReportWrite, SpecsAreVegaLiteWithTheExpectedMarksAndFronts) {
  fs::path run = copyFixture("lodbench_report_specs");
  writeNoHtml(run);
  fs::path dir = run / "report";
  json manifest = readJson(dir / "manifest.json");
  ASSERT_EQ(manifest["charts"].size(), 7u);
  for (auto& c : manifest["charts"]) {
    json spec = readJson(dir / c["spec"].get<std::string>());
    EXPECT_EQ(spec["$schema"], kVegaLiteSchema);
    EXPECT_TRUE(fs::is_regular_file(dir / spec["data"]["url"].get<std::string>())) << c["id"];
    EXPECT_TRUE(spec["title"]["text"].is_string());
  }

  // One row of panels per path, mean and p95 error side by side, each on its own axes.
  json speed = readJson(dir / "charts/speed_gpu_ms.vl.json");
  ASSERT_EQ(speed["vconcat"].size(), 2u);
  json cell = speed["vconcat"][1]["hconcat"][1];
  EXPECT_EQ(cell["title"], "lowalt \u00b7 p95 error");
  json layers = cell["layer"];
  ASSERT_EQ(layers.size(), 4u) << "no errbound case: no reference-front layer";
  EXPECT_EQ(layers[0]["mark"]["type"], "line");
  EXPECT_EQ(layers[0]["transform"][1]["filter"], "datum.on_front && !datum.errbound");
  EXPECT_EQ(layers[1]["mark"]["type"], "point");
  EXPECT_EQ(layers[1]["encoding"]["x"]["field"], "err_px");
  EXPECT_EQ(layers[1]["encoding"]["x"]["title"].get<std::string>().rfind("p95 error (px)", 0), 0u);
  EXPECT_EQ(speed["vconcat"][1]["hconcat"][0]["layer"][1]["encoding"]["x"]["title"].get<std::string>().rfind(
                "mean error (px)", 0),
            0u);
  EXPECT_EQ(layers[1]["encoding"]["y"]["field"], "gpu_ms");
  EXPECT_NE(layers[1]["encoding"]["y"]["title"].get<std::string>().find("GPU ms"), std::string::npos);
  EXPECT_EQ(layers[1]["encoding"]["color"]["scale"]["domain"], json({"uniform", "sphere", "phong"}));
  EXPECT_EQ(layers[1]["encoding"]["color"]["scale"]["range"],
            json({schemeColour("uniform"), schemeColour("sphere"), schemeColour("phong")}));
  // Each point labelled with its parameter value, in the page and in the SVG/PNG exports.
  EXPECT_EQ(layers[2]["mark"]["type"], "text");
  EXPECT_EQ(layers[2]["encoding"]["text"]["field"], "value");
  EXPECT_EQ(layers[2]["encoding"]["x"]["field"], "err_px");
  EXPECT_EQ(layers[3]["mark"]["type"], "text");
  EXPECT_EQ(layers[3]["encoding"]["y"]["value"], "height");  // lower-left corner
  EXPECT_NE(layers[3]["mark"]["text"].get<std::string>().find("better (faster"), std::string::npos);

  // Fronts: within a scheme, path and error kind, a point is on the front iff nothing dominates it.
  json rows = readJson(dir / "data/speed_gpu_ms.json");
  for (auto& a : rows) {
    bool dominated = false;
    for (auto& b : rows)
      if (a["scheme"] == b["scheme"] && a["scenario"] == b["scenario"] && a["error"] == b["error"] &&
          b["err_px"] <= a["err_px"] && b["gpu_ms"] <= a["gpu_ms"] &&
          (b["err_px"] < a["err_px"] || b["gpu_ms"] < a["gpu_ms"]))
        dominated = true;
    EXPECT_EQ(a["on_front"].get<bool>(), !dominated) << a.dump();
  }
  // 11 ok cases, one without error metrics, two error kinds.
  EXPECT_EQ(rows.size(), 2u * 10u);

  json hist = readJson(dir / "charts/triangle_sizes.vl.json");
  EXPECT_EQ(hist["spec"]["mark"]["type"], "bar");
  EXPECT_EQ(hist["spec"]["encoding"]["x"]["sort"], json(histogramBinLabels()));
  EXPECT_EQ(histogramBinLabels().size(), 15u);
  EXPECT_EQ(histogramBinLabels()[1], "1/8-1/4");
  EXPECT_EQ(histogramBinLabels()[13], "512-1024");
  std::map<std::string, double> share;
  for (auto& r : readJson(dir / "data/triangle_sizes.json")) share[r["case_id"]] += r["share"].get<double>();
  EXPECT_EQ(share.size(), 10u);  // ok cases with a histogram: all but the timing-only one
  for (auto& [id, total] : share) EXPECT_NEAR(total, 100.0, 1e-9) << id;

  json timeline = readJson(dir / "data/timeline.json");
  size_t frames = 0;
  json summary = readJson(run / "summary.json");
  for (auto& c : summary["cases"])
    if (c["status"] == "ok")
      frames += readJson(run / "cases" / (c["case_id"].get<std::string>() + ".json"))["frames"].size();
  EXPECT_EQ(timeline.size(), frames);
  json err = readJson(dir / "charts/timeline_error.vl.json");
  EXPECT_EQ(err["transform"][0]["filter"], "isValid(datum.err_mean_px)");
  EXPECT_EQ(err["spec"]["layer"][1]["mark"]["type"], "point");
}

TEST(ReportWrite, RunWithoutMetricsLeavesChartsOutWithNotes) {
  fs::path run = copyFixture("lodbench_report_nometrics");
  dropMetrics(run);
  ReportOutput out = writeNoHtml(run);
  EXPECT_EQ(out.charts, 3);  // GPU ms and triangle timelines, cost vs parameter
  EXPECT_EQ(out.omittedCharts, 5);
  json manifest = readJson(run / "report/manifest.json");
  std::vector<std::string> omitted;
  for (auto& o : manifest["omitted"]) omitted.push_back(o["id"]);
  EXPECT_EQ(omitted, (std::vector<std::string>{"speed_gpu_ms", "speed_triangles", "triangle_sizes", "timeline_error",
                                               "timeline_coverage"}));
  EXPECT_FALSE(fs::exists(run / "report/charts/speed_gpu_ms.vl.json"));
  std::string md = readText(run / "report/report.md");
  EXPECT_NE(md.find("> GPU time vs screen-space error: left out, no case has both a cost and a screen-space error"),
            std::string::npos);
  EXPECT_NE(md.find("Columns left out, no case has them: error mean px, error p95 px, PSNR dB, SSIM, cracks px max, "
                    "missing terrain px max, extra terrain px max, popping mean, surplus, measured frames."),
            std::string::npos);
  // Scheme counter columns only for schemes in the run (none of this run's has one).
  EXPECT_EQ(tableRow(md, "| sphere | flyover |"), "| sphere | flyover | 2 / 0 / 0 | – | – | – | – | – | – | – |");
}

TEST(ReportCli, WritesReportAndRejectsNonRuns) {
  fs::path run = copyFixture("lodbench_report_cli");
  auto sh = [](const std::string& args) {
    std::string cmd = std::string(LODBENCH_BINARY) + " " + args + " 2>&1";
    std::string text;
    FILE* p = popen(cmd.c_str(), "r");
    std::array<char, 4096> buf{};
    while (fgets(buf.data(), int(buf.size()), p)) text += buf.data();
    int status = pclose(p);
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, text);
  };
  auto [code, text] = sh("report " + run.string() + " --no-html --frames 0,6 --out " + (run / "r2").string());
  EXPECT_EQ(code, 0) << text;
  EXPECT_TRUE(fs::is_regular_file(run / "r2/report.md")) << text;
  std::tie(code, text) = sh("report " + run.string() + " --no-html --frames 3");
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("--frames 3: no case has images of this frame."), std::string::npos) << text;
  std::tie(code, text) = sh("report /nonexistent/run");
  EXPECT_EQ(code, 2) << text;
  EXPECT_NE(text.find("/nonexistent/run: not a lodbench run directory"), std::string::npos) << text;
}
