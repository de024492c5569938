// The report's light page and its views: images linked (not embedded) and lazily loaded, PNGs RGB
// and compressed, the answer's margin against the run-to-run noise, the side-by-side view's choice
// of frame and settings, the small-multiple charts, and a definition for every table column.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "render/image_io.h"
#include "report/charts.h"
#include "report/report_answer.h"
#include "report/report_glossary.h"
#include "report/report_images.h"
#include "report/report_side_by_side.h"
#include "report_fixture.h"
#include "schemes/registry.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace lb;
using namespace lb::test;

namespace {

// A case with a median GPU time, a mean error and one timed frame per repetition.
ReportCase timedCase(const std::string& scheme, double param, std::vector<double> repMs, double err) {
  ReportCase c;
  c.scheme = scheme;
  c.params = {{"p", param}};
  c.paramsLabel = "p=" + formatValue(param);
  c.label = scheme + " " + c.paramsLabel;
  c.id = scheme + "-p" + formatValue(param);
  c.status = "ok";
  c.scenario = "flyover";
  c.summary = {{"gpu_ms", {{"median", medianOf(repMs)}}}, {"err_mean_px", {{"mean", err}}}};
  for (double ms : repMs) c.frames.push_back({{"gpu_ms", ms}});
  return c;
}

ReportRun runOf(std::vector<ReportCase> cases, int repetitions) {
  ReportRun run;
  run.cases = std::move(cases);
  run.scenarios = {"flyover"};
  for (auto& c : run.cases) {
    if (std::find(run.schemes.begin(), run.schemes.end(), c.scheme) == run.schemes.end())
      run.schemes.push_back(c.scheme);
    if (std::find(run.paramLabels.begin(), run.paramLabels.end(), c.paramsLabel) == run.paramLabels.end())
      run.paramLabels.push_back(c.paramsLabel);
  }
  run.context = {{"device", "llvmpipe"}, {"config", {{"repetitions", repetitions}}}};
  return run;
}

}  // namespace

TEST(ReportAnswer, GivesTheMarginAndJudgesItAgainstTheRunToRunSpread) {
  // sphere leads phong by 0.2 ms (1.1 against 1.3); uniform is outside the error cap.
  auto answerFor = [](std::vector<double> sphereReps, int reps) {
    return openingAnswer(runOf({timedCase("sphere", 4, sphereReps, 0.1), timedCase("phong", 4, {1.3, 1.3, 1.3}, 0.1),
                                timedCase("uniform", 8, {5, 5, 5}, 1.0)},
                               reps))[0];
  };
  const std::string margin =
      "Runner-up, the fastest other scheme within that error: phong p=4 at 1.3 ms, a margin of 0.2 ms (18.2%)";
  // sphere's repetitions spread 0.4 ms (1.0 .. 1.4): the 0.2 ms lead is within noise.
  std::string a = answerFor({1.0, 1.1, 1.4}, 3);
  EXPECT_NE(a.find(margin + ": within noise (rule: the margin against the larger of the two cases' run-to-run "
                            "spreads, max - min of their 3 per-repetition medians, here 0.4 ms), so the two are not "
                            "told apart."),
            std::string::npos)
      << a;
  // Spread 0.1 ms: the lead is larger than the noise.
  a = answerFor({1.05, 1.1, 1.15}, 3);
  EXPECT_NE(a.find(margin + ": larger than the noise (rule: "), std::string::npos) << a;
  EXPECT_NE(a.find("here 0.1 ms)."), std::string::npos) << a;
  // One repetition: nothing to judge by, and it says so.
  a = answerFor({1.0, 1.1, 1.4}, 1);
  EXPECT_NE(a.find(margin + "; the run has one repetition, so there is no run-to-run spread to judge the margin by"),
            std::string::npos)
      << a;
  // Only one scheme under the cap: no runner-up.
  a = openingAnswer(runOf({timedCase("sphere", 4, {1, 1, 1}, 0.1), timedCase("sphere", 8, {3, 3, 3}, 0.2),
                           timedCase("phong", 8, {2, 2, 2}, 0.9)},
                          3))[0];
  EXPECT_NE(a.find("No other scheme has a case within that error, so there is no runner-up"), std::string::npos) << a;
}

TEST(ReportImages, PngsAreRgbWhenOpaqueWithTheSamePixels) {
  const int w = 7, h = 5;
  std::vector<uint8_t> px(size_t(w) * h * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = i % 4 == 3 ? 255 : uint8_t(i * 37);
  const fs::path dir = fs::path(::testing::TempDir()) / "lodbench_png_rgb";
  fs::create_directories(dir);
  auto written = [&](const std::string& name, const std::vector<uint8_t>& rgba) {
    writePng((dir / name).string(), w, h, rgba);
    std::ifstream f(dir / name, std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), {});
    int x = 0, y = 0, n = 0;
    unsigned char* back = stbi_load((dir / name).c_str(), &x, &y, &n, 4);
    std::vector<uint8_t> got(back, back + size_t(w) * h * 4);
    stbi_image_free(back);
    EXPECT_EQ(got, rgba) << name << ": the pixels read back are the ones written";
    return std::pair<int, int>{bytes.at(25), n};  // IHDR colour type: 2 RGB, 6 RGBA
  };
  EXPECT_EQ(written("opaque.png", px), (std::pair<int, int>{2, 3}));
  px[4 * 11 + 3] = 128;  // one translucent pixel keeps the alpha channel
  EXPECT_EQ(written("translucent.png", px), (std::pair<int, int>{6, 4}));
  EXPECT_EQ(pngSize((dir / "opaque.png").string()), (std::pair<int, int>{w, h}));
  EXPECT_EQ(pngSize((dir / "missing.png").string()), (std::pair<int, int>{0, 0}));
}

TEST(ReportPage, ImagesAreLinkedLazilyWithTheirSizeNotEmbedded) {
  fs::path run = copyFixture("lodbench_report_links");
  writeNoHtml(run);
  const std::string html = readText(run / "report/body.html");
  const std::regex img("<img ([^>]*)>");
  size_t n = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it, ++n) {
    const std::string attrs = (*it)[1];
    std::smatch src;
    ASSERT_TRUE(std::regex_search(attrs, src, std::regex("src=\"\\.\\./(images/[^\"]+\\.png)\""))) << attrs;
    EXPECT_TRUE(fs::is_regular_file(run / src[1].str())) << attrs;
    EXPECT_NE(attrs.find("loading=\"lazy\""), std::string::npos) << attrs;
    auto [w, h] = pngSize((run / src[1].str()).string());
    EXPECT_NE(attrs.find("width=\"" + std::to_string(w) + "\" height=\"" + std::to_string(h) + "\""), std::string::npos)
        << attrs;
  }
  EXPECT_GT(n, 0u);
  EXPECT_EQ(html.find("data:image"), std::string::npos);
}

TEST(ReportSideBySide, OneFrameEverySchemeAtTheSettingNearestTheCommonError) {
  fs::path run = copyFixture("lodbench_side_by_side");
  // Images of frame 4 for every finished flyover case, frame 2 for two only: frame 4 has the most schemes.
  ReportRun before = loadReportRun(run.string());
  const fs::path png = *fs::directory_iterator(run / "images");
  for (auto& c : before.cases) {
    if (c.scenario != before.scenarios[0] || c.status != "ok") continue;
    for (const char* m : {"shaded", "error"}) fs::copy_file(png, run / "images" / (c.id + "_f4_" + m + ".png"));
  }
  ReportRun r = loadReportRun(run.string());
  SideBySide v = chooseSideBySide(r);
  EXPECT_EQ(v.scenario, r.scenarios[0]);
  EXPECT_EQ(v.frame, 4);
  // The error a case is compared by: its frame 4's own where measured, else its mean.
  auto errorOf = [](const ReportCase& c) {
    for (auto& f : c.frames)
      if (frameValue(f, "frame") == 4.0 && frameValue(f, "err_mean_px")) return *frameValue(f, "err_mean_px");
    return *summaryStat(c.summary, "err_mean_px", "mean");
  };
  std::vector<double> errors;
  std::set<std::string> schemes;
  for (auto& c : r.cases)
    if (c.scenario == v.scenario && c.status == "ok") {
      schemes.insert(c.scheme);
      errors.push_back(errorOf(c));
    }
  EXPECT_DOUBLE_EQ(v.target, medianOf(errors));
  ASSERT_EQ(v.rows.size(), schemes.size()) << "one row per scheme";
  for (auto& row : v.rows) {
    // Matched: no other case of the scheme is nearer the target; not matched: none within the factor.
    for (auto& c : r.cases) {
      if (c.scheme != row.c->scheme || c.scenario != v.scenario || c.status != "ok") continue;
      double d = std::fabs(std::log(errorOf(c) / v.target));
      if (row.matched)
        EXPECT_LE(std::fabs(std::log(*row.error / v.target)), d + 1e-12) << c.id;
      else
        EXPECT_GT(d, std::log(kMatchFactor)) << c.id;
    }
  }
  auto [md, html] = sideBySideSection(r, "..");
  EXPECT_NE(html.find("<h2 id=\"side-by-side\">"), std::string::npos);
  EXPECT_NE(html.find("id=\"flip-button\""), std::string::npos);
  EXPECT_NE(html.find("data-scheme=\"" + v.rows[0].c->scheme + "\" data-mode=\"error\""), std::string::npos);
  EXPECT_EQ(html.find("data-mode=\"heatmap\""), std::string::npos) << "no heat-map images: no column";
  // The fixture alone has no frame imaged for two schemes: no view, no empty section.
  EXPECT_EQ(chooseSideBySide(before).frame, -1);
  EXPECT_EQ(sideBySideSection(before, "..").second, "");
}

TEST(ReportSideBySide, ASchemeWithNoSettingNearTheTargetShowsItsDefault) {
  // Errors 1, 5 (uniform), 6 (sphere), 7 (phong), and distance far off at 40 and 60: target 6.5.
  const Scheme* distance = findScheme("distance");
  ASSERT_NE(distance, nullptr);
  double def = 0;
  for (const ParamSpec& p : distance->info().params)
    if (p.name == distance->info().mainParam) def = p.defaultValue;
  std::vector<ReportCase> cases = {timedCase("uniform", 2, {1}, 1),         timedCase("uniform", 4, {1}, 5),
                                   timedCase("sphere", 4, {1}, 6),          timedCase("phong", 4, {1}, 7),
                                   timedCase("distance", def * 2, {1}, 40), timedCase("distance", def, {1}, 60)};
  for (auto& c : cases) c.params = {{findScheme(c.scheme)->info().mainParam, c.params["p"]}};
  ReportRun run = runOf(cases, 1);
  for (auto& c : run.cases) run.images[c.id][5] = {{"shaded", "images/" + c.id + "_f5_shaded.png"}};
  run.images[run.cases[0].id][9] = {{"shaded", "images/only-one-scheme.png"}};
  SideBySide v = chooseSideBySide(run);
  EXPECT_EQ(v.frame, 5);
  EXPECT_EQ(v.target, 6.5);
  ASSERT_EQ(v.rows.size(), 4u);
  EXPECT_EQ(v.rows[0].c, &run.cases[1]) << "uniform: 5 px is nearer 6.5 than 1 px";
  EXPECT_TRUE(v.rows[0].matched);
  EXPECT_TRUE(v.rows[1].matched && v.rows[2].matched);
  EXPECT_EQ(v.rows[3].c, &run.cases[5]) << "distance: nothing within 1.5x of 6.5 px, so its default setting";
  EXPECT_FALSE(v.rows[3].matched);
  EXPECT_NE(sideBySideSection(run, "..").second.find("no match: default setting"), std::string::npos);
}

TEST(ReportCharts, HistogramsAndTimelinesAreOnePanelPerSchemeInAGrid) {
  fs::path run = copyFixture("lodbench_report_panels");
  writeNoHtml(run);
  for (const char* chart : {"triangle_sizes", "timeline_gpu_ms"}) {
    json spec = readJson(run / "report/charts" / (std::string(chart) + ".vl.json"));
    EXPECT_EQ(spec["columns"], kPanelColumns) << chart;
    EXPECT_EQ(spec["facet"]["field"], "panel") << chart;
    const json& enc =
        spec["spec"].contains("encoding") ? spec["spec"]["encoding"] : spec["spec"]["layer"][0]["encoding"];
    EXPECT_EQ(enc["color"]["field"], "setting") << chart;
    // Every panel's header names its settings' values, so an export says which bar is which.
    const std::string labels = spec["facet"]["header"]["labelExpr"];
    EXPECT_NE(labels.find("\"uniform \u00b7 flyover: level 4 / 16\""), std::string::npos) << labels;
  }
  // The ramp: the setting with the smaller value first.
  for (auto& row : readJson(run / "report/data/triangle_sizes.json"))
    if (row["scheme"] == "uniform") EXPECT_EQ(row["setting"], row["params"] == "level=4" ? 1 : 2) << row.dump();
}

TEST(ReportPage, EveryTableColumnIsDefinedAndItsHeaderLinksThere) {
  fs::path run = copyFixture("lodbench_report_glossary");
  writeNoHtml(run);
  const std::string html = readText(run / "report/body.html");
  std::set<std::string> defined;
  const std::regex dt("<dt id=\"([^\"]+)\">");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), dt); it != std::sregex_iterator(); ++it)
    defined.insert((*it)[1]);
  const std::regex th("<th>(.*?)</th>");
  size_t headers = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), th); it != std::sregex_iterator(); ++it, ++headers) {
    std::smatch link;
    const std::string cell = (*it)[1];
    ASSERT_TRUE(std::regex_search(cell, link, std::regex("^<a class=\"def\" href=\"#([^\"]+)\">"))) << cell;
    EXPECT_TRUE(defined.count(link[1])) << cell;
  }
  EXPECT_GT(headers, 20u);
  EXPECT_EQ(html.find("no definition recorded"), std::string::npos);
  for (const char* h : {"CPU ms median", "harness CPU ms", "FPS median"})
    EXPECT_TRUE(columnDefinition(loadReportRun(run.string()), h).has_value()) << h;
  EXPECT_EQ(definitionAnchor("GPU ms p95"), "def-gpu-ms-p95");
  EXPECT_FALSE(columnDefinition(loadReportRun(run.string()), "no such column").has_value());
}
