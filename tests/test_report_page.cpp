// The report page (issues 12 and 14) on the committed fixture run: the opening answer, the metric
// notes and their link, tables that scroll inside their box, the image legends against the code
// that paints the images, worst frames without images, and the scenario summary grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <tuple>

#include "error.h"
#include "metrics/cracks.h"
#include "render/image_io.h"
#include "replay/measure.h"
#include "report/report.h"
#include "report/report_answer.h"
#include "report/report_images.h"
#include "report/report_tables.h"
#include "report/run_data.h"
#include "report/scenario_table.h"
#include "report_fixture.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using namespace lb::test;

// Makes the fixture a scenario run: config name "scenario-..." and a description naming a metric.
void makeScenario(const fs::path& run, const std::string& metric) {
  json r = readJson(run / "run.json");
  r["context"]["config"]["name"] = "scenario-fixture";
  r["context"]["config"]["description"] = "Fixture as a scenario. Shows in " + metric + ".";
  std::ofstream(run / "run.json") << r.dump();
}

}  // namespace

TEST(ReportAnswer, NamesTheFastestCaseWithinTheMedianErrorAndTheMostAccurateWithinTheMedianCost) {
  ReportRun run = loadReportRun(kFixture.string());
  std::vector<std::string> answer = openingAnswer(run);
  ASSERT_EQ(answer.size(), run.scenarios.size() + 1);  // one per scenario, then the device caveat
  EXPECT_NE(answer.back().find("llvmpipe"), std::string::npos);
  EXPECT_NE(answer.back().find("software rasterizer"), std::string::npos);
  for (size_t i = 0; i < run.scenarios.size(); ++i) {
    // Independently: the finished cases of this scenario with both figures, and the two choices.
    std::vector<const ReportCase*> cs;
    std::vector<double> errs, gpus;
    for (auto& c : run.cases) {
      auto g = summaryStat(c.summary, "gpu_ms", "median"), e = summaryStat(c.summary, "err_mean_px", "mean");
      if (c.scenario != run.scenarios[i] || c.status != "ok" || !g || !e) continue;
      cs.push_back(&c);
      errs.push_back(*e);
      gpus.push_back(*g);
    }
    ASSERT_FALSE(cs.empty());
    const double errCap = medianOf(errs), gpuCap = medianOf(gpus);
    const ReportCase *fast = nullptr, *exact = nullptr;
    for (size_t k = 0; k < cs.size(); ++k) {
      if (errs[k] <= errCap && (!fast || gpus[k] < *summaryStat(fast->summary, "gpu_ms", "median"))) fast = cs[k];
      if (gpus[k] <= gpuCap && (!exact || errs[k] < *summaryStat(exact->summary, "err_mean_px", "mean"))) exact = cs[k];
    }
    const std::string& a = answer[i];
    EXPECT_EQ(a.rfind(run.scenarios[i] + ": ", 0), 0u) << a;
    EXPECT_NE(a.find(std::to_string(cs.size()) +
                     " cases with an error pass. Fastest at a mean screen-space error of "
                     "at most " +
                     formatValue(errCap) + " px (the median error): " + fast->label + " (case " + fast->id + "): "),
              std::string::npos)
        << a;
    const std::string exactName = exact == fast ? exact->label + " again" : exact->label + " (case " + exact->id + ")";
    EXPECT_NE(a.find("Most accurate within " + formatValue(gpuCap) + " ms of GPU time (the median): " + exactName),
              std::string::npos)
        << a;
    EXPECT_NE(a.find("triangles (the median; triangle counts do not depend on the device): "), std::string::npos) << a;
  }
  EXPECT_EQ(medianOf({3, 1, 2}), 2);
  EXPECT_EQ(medianOf({4, 1, 2, 3}), 2.5);
}

TEST(ReportAnswer, SaysSoWhenThereIsNoErrorPass) {
  fs::path run = copyFixture("lodbench_answer_noerror");
  for (auto& e : fs::directory_iterator(run / "cases")) {
    json c = readJson(e.path());
    c["summary"].erase("err_mean_px");
    std::ofstream(e.path()) << c.dump();
  }
  json s = readJson(run / "summary.json");
  for (auto& c : s["cases"]) c["summary"].erase("err_mean_px");
  std::ofstream(run / "summary.json") << s.dump();
  std::vector<std::string> answer = openingAnswer(loadReportRun(run.string()));
  ASSERT_EQ(answer.size(), 3u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NE(answer[i].find("no finished case has both a GPU time and an error pass"), std::string::npos) << answer[i];
    EXPECT_EQ(answer[i].find("Fastest"), std::string::npos) << answer[i];
  }
}

TEST(ReportPage, TablesScrollInTheirBoxWithNotesLinkingTheFormatCopy) {
  fs::path run = copyFixture("lodbench_report_page");
  writeNoHtml(run);
  const std::string html = readText(run / "report/body.html");
  EXPECT_NE(html.find("<div class=\"table-wrap\"><table class=\"cases sticky\">"), std::string::npos);
  EXPECT_NE(html.find("<div class=\"table-wrap\"><table class=\"stability sticky\">"), std::string::npos);
  // Every table is inside a scroll box: as many boxes as tables.
  auto count = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t at = html.find(needle); at != std::string::npos; at = html.find(needle, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<div class=\"table-wrap\"><table"), count("<table"));
  // One note before the stability table and one before the case table, each with the link.
  EXPECT_EQ(count("<aside class=\"howto\">"), 2u);
  EXPECT_EQ(count("<a href=\"results-format.md\">"), 2u);
  EXPECT_NE(html.find("it beat errbound at equal error: a finding, not a bug"), std::string::npos);
  EXPECT_EQ(readText(run / "report/results-format.md"),
            readText(fs::path(LODBENCH_SOURCE_DIR) / "docs/results-format.md"));
  EXPECT_NE(html.find("<p class=\"answer\">"), std::string::npos);
  EXPECT_LT(html.find("<p class=\"answer\">"), html.find("<h2 id=\"context\">"));  // the answer comes first
}

TEST(ReportPage, WorstFramesWithoutImagesAreNamedAndThoseWithImagesHaveStrips) {
  fs::path run = copyFixture("lodbench_report_worst");
  writeNoHtml(run);
  const std::string html = readText(run / "report/body.html");
  ReportRun r = loadReportRun(run.string());
  int missing = 0, present = 0;
  for (auto& c : r.cases)
    for (int f : worstFrames(c)) {
      const std::string anchor = "id=\"img-" + c.id + "-f" + std::to_string(f) + "\"";
      const std::string marker = "data-case=\"" + c.id + "\" data-frame=\"" + std::to_string(f) + "\"";
      const bool hasImages = r.images.count(c.id) && r.images.at(c.id).count(f);
      EXPECT_EQ(html.find(anchor) != std::string::npos, hasImages) << c.id << " f" << f;
      EXPECT_EQ(html.find(marker) != std::string::npos, !hasImages) << c.id << " f" << f;
      (hasImages ? present : missing)++;
    }
  EXPECT_GT(missing, 0);  // the fixture keeps images of two frames only
  EXPECT_GT(present, 0);
}

TEST(ReportLegend, ColoursAreTheOnesThePaintingCodeUses) {
  // heat(): 1 -> (0, 0, 0.5), 8 -> (0.5, 1, 0.5), 64 -> (0.5, 0, 0); the shader text this mirrors.
  EXPECT_EQ(heatColour(1), "#000080");
  EXPECT_EQ(heatColour(8), "#80ff80");
  EXPECT_EQ(heatColour(64), "#800000");
  EXPECT_EQ(heatColour(0.5), heatColour(1));
  EXPECT_EQ(heatColour(128), heatColour(64));
  const std::string frag = [] {
    std::ifstream f(fs::path(LODBENCH_SOURCE_DIR) / "shaders/terrain.frag");
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }();
  EXPECT_NE(frag.find("float t = clamp(log2(max(level, 1.0)) / 6.0, 0.0, 1.0);"), std::string::npos)
      << "terrain.frag's heat() changed: update heatColour() in harness/report/report_images.cpp";
  EXPECT_NE(frag.find("vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0))"),
            std::string::npos);
  // The error map through the function that writes it.
  const std::vector<float> px{0, 0.5f, 2, 4.5f, 8, 100};
  RgbaImage img = errorImage(px, int(px.size()), 1);
  for (size_t i = 0; i < px.size(); ++i) {
    EXPECT_EQ(int(img.px[i * 4]), errorGrey(px[i])) << px[i];
    EXPECT_EQ(int(img.px[i * 4 + 1]), errorGrey(px[i])) << px[i];
  }
  EXPECT_EQ(errorGrey(0), 0);
  EXPECT_EQ(errorGrey(8), 255);
  RgbaImage none = errorImage({-1}, 1, 1);  // no terrain: the legend's sky swatch
  EXPECT_EQ(std::vector<uint8_t>(none.px.begin(), none.px.begin() + 3),
            (std::vector<uint8_t>{kSkyRgba[0], kSkyRgba[1], kSkyRgba[2]}));
  EXPECT_NE(legendHtml("error").find("#c4d2e2"), std::string::npos);
  // The crack mask: red crack pixels, the rest dimmed to a third.
  RgbaImage frame{2, 1, {90, 120, 150, 255, 90, 120, 150, 255}};
  RgbaImage mask = crackMaskImage(frame, {1, 0});
  EXPECT_EQ(std::vector<uint8_t>(mask.px.begin(), mask.px.begin() + 3), (std::vector<uint8_t>{255, 0, 0}));
  EXPECT_EQ(std::vector<uint8_t>(mask.px.begin() + 4, mask.px.begin() + 7), (std::vector<uint8_t>{30, 40, 50}));
  EXPECT_NE(legendHtml("cracks").find("#ff0000"), std::string::npos);
  EXPECT_EQ(legendHtml("shaded"), "");
}

TEST(ReportScenario, GridScoresEachScenarioFromItsBestToItsWorstCase) {
  EXPECT_EQ(badness(2, 2, 6), 0);
  EXPECT_EQ(badness(6, 2, 6), 1);
  EXPECT_EQ(badness(3, 2, 6), 0.25);
  EXPECT_EQ(badness(30, 40, 20), 0.5);  // PSNR: best is the highest
  EXPECT_EQ(badness(5, 5, 5), 0);       // all equal: nobody is worse
  fs::path run = copyFixture("lodbench_report_grid");
  makeScenario(run, "err_p95_px");
  writeNoHtml(run);
  const std::string md = readText(run / "report/report.md");
  const std::string html = readText(run / "report/body.html");
  ASSERT_NE(md.find("## Scenario"), std::string::npos);
  EXPECT_NE(md.find("What to look for: Fixture as a scenario. Shows in err_p95_px."), std::string::npos);
  ReportRun r = loadReportRun(run.string());
  // Per scenario row: exactly one best [0.00] and, the values differing, one worst [1.00].
  for (auto& scenario : r.scenarios) {
    size_t at = md.find("\n| " + scenario + " |");
    ASSERT_NE(at, std::string::npos) << scenario;
    const std::string row = md.substr(at + 1, md.find('\n', at + 1) - at - 1);
    std::map<std::string, int> scores;
    const std::regex score(R"(\[(\d\.\d\d)\])");
    for (auto it = std::sregex_iterator(row.begin(), row.end(), score); it != std::sregex_iterator(); ++it)
      scores[(*it)[1]]++;
    EXPECT_EQ(scores["0.00"], 1) << row;
    EXPECT_EQ(scores["1.00"], 1) << row;
  }
  // Every grid link has its row in the per-case table, and every finished case with the metric a cell.
  const std::regex link(R"re(<a href="#(scn-[^"]+)">)re");
  int links = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it, ++links)
    EXPECT_NE(html.find("<tr id=\"" + (*it)[1].str() + "\">"), std::string::npos) << (*it)[1];
  int withMetric = 0;
  for (auto& c : r.cases)
    if (c.status == "ok" && std::any_of(c.frames.begin(), c.frames.end(),
                                        [](const json& f) { return frameValue(f, "err_p95_px").has_value(); }))
      ++withMetric;
  EXPECT_EQ(links, withMetric);
  EXPECT_NE(html.find("<table class=\"grid sticky\">"), std::string::npos);
}

TEST(ReportScenario, SweepFolderGetsOneSummaryGridOverItsScenarioRuns) {
  const fs::path sweep = fs::path(::testing::TempDir()) / "lodbench_scenario_sweep";
  fs::remove_all(sweep);
  fs::create_directories(sweep / "configs");  // run-scenarios.sh keeps its config copies here: not a run
  const std::map<std::string, std::string> metrics{{"a-errors", "err_p95_px"}, {"b-popping", "pop_mean"}};
  for (auto& [name, metric] : metrics) {
    fs::copy(kFixture, sweep / name, fs::copy_options::recursive);
    makeScenario(sweep / name, metric);
    json r = readJson(sweep / name / "run.json");
    r["context"]["config"]["name"] = "scenario-" + name;
    std::ofstream(sweep / name / "run.json") << r.dump();
    writeNoHtml(sweep / name);
  }
  ReportOptions o;
  o.runDir = sweep.string();
  o.html = false;
  ReportOutput out = writeReport(o);
  EXPECT_EQ(out.dir, (sweep / "report").string());
  const std::string md = readText(sweep / "report/report.md");
  ASSERT_NE(md.find("## Summary grid"), std::string::npos);
  ReportRun fixture = loadReportRun(kFixture.string());
  // One row per scenario run and path, each naming its metric and linking to the run's report.
  for (auto& [name, metric] : metrics)
    for (auto& scenario : fixture.scenarios)
      EXPECT_NE(md.find("| [" + name + " / " + scenario + "](../" + name + "/report/report.md) | `" + metric + "` |"),
                std::string::npos)
          << name << " " << scenario;
  // The per-run reports have no report.html here (html off): said, not hidden.
  EXPECT_EQ(out.notes.size(), metrics.size());
  EXPECT_THROW(
      {
        ReportOptions bad;
        bad.runDir = (sweep / "configs").string();
        writeReport(bad);
      },
      InputError);
}

TEST(ReportScenario, DifferenceScenariosScoreEachRowAgainstTheControlRow) {
  ReportRun run;
  run.name = "scenario-origin";
  run.context = {{"config", {{"description", "Far. Shows in the difference from the at-origin case: err_mean_px."}}}};
  run.scenarios = {"p", "p-at9"};
  // Scheme u: 1 at the origin, 4 far (+3); scheme s: 2 and 2.5 (+0.5).
  const std::vector<std::tuple<std::string, std::string, double>> values{
      {"u", "p", 1}, {"s", "p", 2}, {"u", "p-at9", 4}, {"s", "p-at9", 2.5}};
  for (auto& [label, scenario, v] : values) {
    ReportCase c;
    c.id = label + "_" + scenario;
    c.label = c.scheme = label;
    c.scenario = scenario;
    c.status = "ok";
    c.frames = json::array({{{"frame", 0}, {"err_mean_px", v}}});
    run.cases.push_back(c);
  }
  EXPECT_EQ(controlScenario(run), "p");
  auto rows = gridRows(run, {"u", "s"}, "err_mean_px", "", "");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].first, "p (control)");
  EXPECT_EQ(rows[0].second[0].md, "[1](#scn-u_p)");  // plain value, no score, no colour
  EXPECT_EQ(rows[0].second[0].tdAttrs, "");
  EXPECT_EQ(rows[1].first, "p-at9 (difference)");
  EXPECT_EQ(rows[1].second[0].md, "+3 [1.00]");
  EXPECT_EQ(rows[1].second[1].md, "+0.5 [0.00]");
  run.context["config"]["description"] = "Near. Shows in err_mean_px.";  // no control: plain values
  EXPECT_EQ(controlScenario(run), "");
  rows = gridRows(run, {"u", "s"}, "err_mean_px", "", "");
  EXPECT_EQ(rows[1].second[0].md, "4 [1.00]");
  EXPECT_EQ(rows[1].second[1].md, "2.5 [0.00]");
}

// Each row says what it showed: worst and best case, or that the predicted failure did not appear
// when every case reads the same (e.g. no scheme cracks where a seed predicts cracks).
TEST(ReportScenario, OutcomesNameTheWorstCaseOrSayTheFailureDidNotAppear) {
  ReportRun run;
  run.name = "scenario-outcome";
  run.context = {{"config", {{"description", "Cracks. Shows in cracks_pixels."}}}};
  run.scenarios = {"calm", "rough"};
  const std::vector<std::tuple<std::string, std::string, double>> values{
      {"u", "calm", 0}, {"s", "calm", 0}, {"u", "rough", 7}, {"s", "rough", 2}};
  for (auto& [label, scenario, v] : values) {
    ReportCase c;
    c.id = label + "_" + scenario;
    c.label = c.scheme = label;
    c.scenario = scenario;
    c.status = "ok";
    c.frames = json::array({{{"frame", 0}, {"cracks_pixels", v}}});
    run.cases.push_back(c);
  }
  auto o = scenarioOutcomes(run, "cracks_pixels");
  ASSERT_EQ(o.size(), 2u);
  EXPECT_EQ(o[0], "calm: every case reads 0 on cracks_pixels: the predicted failure did not appear here.");
  EXPECT_EQ(o[1], "rough: worst u (7), best s (2) on cracks_pixels.");
  // Higher-is-better metrics: the worst is the lowest.
  for (auto& c : run.cases) c.frames[0]["img_psnr_db"] = c.frames[0]["cracks_pixels"];
  o = scenarioOutcomes(run, "img_psnr_db");
  EXPECT_EQ(o[1], "rough: worst s (2), best u (7) on img_psnr_db.");
  // Difference scenarios: scored on the size of the difference from the control, which is left out.
  run.context["config"]["description"] = "Far. Shows in the difference from the at-origin case: err_mean_px.";
  run.scenarios = {"p", "p-at9"};
  for (auto& c : run.cases) {
    c.scenario = c.scenario == "calm" ? "p" : "p-at9";
    c.frames[0]["err_mean_px"] = c.frames[0]["cracks_pixels"];
  }
  o = scenarioOutcomes(run, "err_mean_px");
  ASSERT_EQ(o.size(), 1u);
  EXPECT_EQ(o[0], "p-at9: worst u (+7), best s (+2) on err_mean_px minus the control's.");
}
