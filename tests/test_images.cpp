// Images for people: sky background, images.resolution with the case's own
// tessellation, worst frames always drawn, readable wireframes, and no effect on what is measured.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "config/config.h"
#include "error.h"
#include "gpu_fixture.h"
#include "metrics/image_metrics.h"
#include "metrics/raycast_shade.h"
#include "render/image_io.h"
#include "replay/case_images.h"
#include "report/report_tables.h"
#include "report/run_data.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

static const std::string kBase = std::string(LODBENCH_SOURCE_DIR) + "/configs";

static std::string errorOf(const std::string& text) {
  try {
    parseConfig(text, "bad.json", kBase);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Images, ResolutionAndWorstAreValidated) {
  const std::string p = "{\"paths\": [\"paths/horizon.csv\"], \"schemes\": [\"sphere\"], \"images\": ";
  Config d = parseConfig(p + "{\"modes\": [\"shaded\"]}}", "ok.json", kBase);
  EXPECT_EQ(d.images.width, 640);
  EXPECT_EQ(d.images.height, 360);
  EXPECT_TRUE(d.images.worst);
  Config c = parseConfig(p + "{\"resolution\": [800, 450], \"worst\": false}}", "ok.json", kBase);
  EXPECT_EQ(c.images.width, 800);
  EXPECT_EQ(c.images.height, 450);
  EXPECT_FALSE(c.images.worst);
  struct Bad {
    std::string images, field;
  };
  for (const Bad& b : std::vector<Bad>{{"{\"resolution\": 640}", "'/images/resolution'"},
                                       {"{\"resolution\": [640]}", "'/images/resolution'"},
                                       {"{\"resolution\": [640, 360, 1]}", "'/images/resolution'"},
                                       {"{\"resolution\": [8, 360]}", "'/images/resolution/0'"},
                                       {"{\"resolution\": [640, 9000]}", "'/images/resolution/1'"},
                                       {"{\"resolution\": [640.5, 360]}", "'/images/resolution/0'"},
                                       {"{\"resolution\": [\"640\", 360]}", "'/images/resolution/0'"},
                                       {"{\"worst\": 1}", "'/images/worst'"}}) {
    std::string e = errorOf(p + b.images + "}");
    EXPECT_NE(e.find("bad.json:1"), std::string::npos) << b.images << ": " << e;
    EXPECT_NE(e.find(b.field), std::string::npos) << b.images << ": " << e;
  }
}

TEST(Images, SizeFollowsTheCaseAspectRatioAndFramesAreListedOnce) {
  ImageRequest r;  // 640 x 360
  EXPECT_EQ(imageSize(320, 180, r), std::make_pair(640, 360));
  EXPECT_EQ(imageSize(1920, 1080, r), std::make_pair(640, 360));
  EXPECT_EQ(imageSize(64, 48, r), std::make_pair(640, 480));  // 4:3 covers 640 x 360
  EXPECT_EQ(imageSize(100, 200, r), std::make_pair(640, 1280));
  r.frames = {1, -1, 3};
  json worst = {{"cracks_pixels", 0}, {"pop_mean", 6}, {"err_p95_px", 3}, {"cracks_analytic", 0}};
  EXPECT_EQ(imageFrames(r, 10, worst), (std::vector<int>{1, 9, 3, 0, 6}));
  r.worst = false;
  EXPECT_EQ(imageFrames(r, 10, worst), (std::vector<int>{1, 9, 3}));
  EXPECT_EQ(imageFrames(r, 10, json()), (std::vector<int>{1, 9, 3}));
}

TEST(Images, ScaleNearestRepeatsPixels) {
  std::vector<uint8_t> mask = {1, 0, 0, 1};  // 2 x 2
  std::vector<uint8_t> big = scaleNearest(mask, 2, 2, 1, 4, 4);
  EXPECT_EQ(big, (std::vector<uint8_t>{1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 1}));
  EXPECT_THROW(scaleNearest(mask, 3, 2, 1, 4, 4), std::invalid_argument);
}

class ImageRender : public lbtest::GpuTest {};

// The image renderer decides the LOD for the case's resolution: the tessellation of a frame drawn
// at twice the size is the case's, level for level; the wireframe's shaded underlay is outside
// the statistics query; and only images for people have the sky.
TEST_F(ImageRender, LargerImagesKeepTheCaseTessellation) {
  const Scheme* sphere = findScheme("sphere");
  ASSERT_NE(sphere, nullptr);
  const CameraPose pose = lbtest::overviewPose();
  RenderSettings small{96, 54, 8};
  Renderer a(lbtest::gpu(), lbtest::testTerrain(), small);
  a.setScheme(*sphere, {{"tri_size", 4}});
  FrameResult ra, rb, rw;
  std::vector<uint8_t> pa = a.renderImage(pose, pose, RenderMode::Shaded, &ra);
  std::vector<float> la = a.capturedLevels();
  RenderSettings big = small;
  big.width = 192, big.height = 108, big.lodWidth = 96, big.lodHeight = 54, big.sky = true;
  Renderer b(lbtest::gpu(), lbtest::testTerrain(), big);
  b.setScheme(*sphere, {{"tri_size", 4}});
  std::vector<uint8_t> pb = b.renderImage(pose, pose, RenderMode::Shaded, &rb);
  EXPECT_EQ(b.capturedLevels(), la);
  EXPECT_GT(ra.stats.clipInvocations, 0u);
  EXPECT_EQ(rb.stats.tcsPatches, ra.stats.tcsPatches);
  EXPECT_EQ(rb.stats.tesInvocations, ra.stats.tesInvocations);
  EXPECT_EQ(rb.stats.clipInvocations, ra.stats.clipInvocations);
  if (lbtest::gpu().enabledFeatures.fillModeNonSolid) {
    std::vector<uint8_t> pw = b.renderImage(pose, pose, RenderMode::Wireframe, &rw);
    EXPECT_EQ(rw.stats.clipInvocations, rb.stats.clipInvocations) << "one frame's triangles, not two";
    EXPECT_EQ(rw.stats.tesInvocations, rb.stats.tesInvocations);
    long differ = 0;
    for (size_t i = 0; i < pw.size(); i += 4)
      differ += pw[i] != pb[i] || pw[i + 1] != pb[i + 1] || pw[i + 2] != pb[i + 2];
    EXPECT_GT(differ, 0) << "lines drawn";
    EXPECT_LT(differ, long(pw.size() / 4)) << "the shaded frame shows between the lines";
  }
  // The view sees past the terrain: magenta there in the measurement render, sky in the image.
  long magentaA = 0, magentaB = 0, skyB = 0;
  for (size_t i = 0; i < pa.size(); i += 4) magentaA += pa[i] == 255 && pa[i + 1] == 0 && pa[i + 2] == 255;
  for (size_t i = 0; i < pb.size(); i += 4) {
    magentaB += pb[i] == 255 && pb[i + 1] == 0 && pb[i + 2] == 255;
    skyB += pb[i] == kSkyRgba[0] && pb[i + 1] == kSkyRgba[1] && pb[i + 2] == kSkyRgba[2];
  }
  EXPECT_GT(magentaA, 0);
  EXPECT_EQ(magentaB, 0);
  EXPECT_GT(skyB, 0);
}

// --- A small run with images of every mode --------------------------------------------------

static Config smallConfig(bool images) {
  std::string text =
      R"({
    "name": "img", "resolution": [96, 54], "grid": 8, "fps": 10, "warmup_frames": 1, "max_frames": 6,
    "terrain": {"type": "procedural", "size": 65, "seed": 3},
    "paths": ["paths/horizon.csv"],
    "schemes": [{"name": "uniform", "params": {"level": 3}}, {"name": "sphere", "params": {"tri_size": 4}}],
    "measure": {"every": 2, "passes": ["error", "image", "cracks", "popping"]},
    "images": )" +
      std::string(images ? R"({"frames": [1], "modes": ["shaded", "heatmap", "wireframe", "error", "cracks"],
                                             "resolution": [192, 108]})"
                         : R"({"frames": [], "modes": []})") +
      "}";
  return parseConfig(text, "img.json", kBase);
}

static fs::path freshDir(const std::string& name) {
  fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  return d;
}

static json readJson(const fs::path& p) {
  std::ifstream f(p);
  return json::parse(f);
}

struct Png {
  int width = 0, height = 0;
  std::vector<uint8_t> px;
  long count(uint8_t r, uint8_t g, uint8_t b) const {
    long n = 0;
    for (size_t i = 0; i + 3 < px.size(); i += 4) n += px[i] == r && px[i + 1] == g && px[i + 2] == b;
    return n;
  }
};

static Png readPng(const fs::path& p) {
  Png out;
  int channels = 0;
  unsigned char* data = stbi_load(p.c_str(), &out.width, &out.height, &channels, 4);
  if (!data) throw std::runtime_error("cannot read " + p.string());
  out.px.assign(data, data + size_t(out.width) * size_t(out.height) * 4);
  stbi_image_free(data);
  return out;
}

class ImageRun : public ::testing::Test {
 protected:
  // ctest runs each test in its own process, possibly two at once: one run per process and directory.
  static void SetUpTestSuite() {
    on_ = freshDir("lodbench_images_on_" + std::to_string(getpid()));
    totalsOn_ = runSweep(smallConfig(true), {on_.string(), false, false});
  }
  static fs::path on_;
  static RunTotals totalsOn_;
};
fs::path ImageRun::on_;
RunTotals ImageRun::totalsOn_;

static const char* const kModes[] = {"shaded", "heatmap", "wireframe", "error", "cracks"};

TEST_F(ImageRun, EveryWorstFrameHasItsImages) {
  ASSERT_EQ(totalsOn_.ok, 2);
  EXPECT_EQ(totalsOn_.validationErrors, 0);
  ReportRun run = loadReportRun(on_.string());
  ASSERT_EQ(run.cases.size(), 2u);
  for (const ReportCase& c : run.cases) {
    SCOPED_TRACE(c.id);
    json record = readJson(on_ / "cases" / (c.id + ".json"));
    std::set<std::string> listed;
    for (auto& f : record["images"]) listed.insert(f.get<std::string>());
    const json& worst = c.summary["worst_frames"];
    ASSERT_TRUE(worst.is_object());
    ASSERT_FALSE(worst.empty());
    std::set<int> frames = {1};  // the configured frame
    for (auto& [metric, f] : worst.items()) frames.insert(f.get<int>());
    for (int f : worstFrames(c)) EXPECT_TRUE(frames.count(f)) << "the report's worst frame " << f;
    for (int f : frames)
      for (const char* m : kModes) {
        std::string file = "images/" + c.id + "_f" + std::to_string(f) + "_" + m + ".png";
        EXPECT_TRUE(listed.count(file)) << file << " not in the case record";
        ASSERT_TRUE(fs::exists(on_ / file)) << file;
        ASSERT_TRUE(run.images[c.id][f].count(m)) << "the report finds " << file;
        Png png = readPng(on_ / file);
        EXPECT_EQ(png.width, 192);
        EXPECT_EQ(png.height, 108);
      }
    EXPECT_EQ(listed.size(), frames.size() * std::size(kModes)) << "each image once";
  }
}

// The ray-cast truth (what image metrics and crack pixels compare against) has magenta where no
// terrain is; the images for people have none anywhere, and sky instead.
TEST_F(ImageRun, ImagesForPeopleHaveSkyWhereTheTruthHasMagenta) {
  ASSERT_EQ(totalsOn_.ok, 2);
  long truthMagenta = 0;
  int truths = 0;
  for (auto& e : fs::directory_iterator(on_ / "truth")) {
    if (e.path().extension() != ".png") continue;
    ++truths;
    truthMagenta += readPng(e.path()).count(kClearRgba[0], kClearRgba[1], kClearRgba[2]);
  }
  ASSERT_GT(truths, 0);
  ASSERT_GT(truthMagenta, 0) << "the horizon path must show the sky for this test to mean anything";
  int images = 0;
  for (auto& e : fs::directory_iterator(on_ / "images")) {
    SCOPED_TRACE(e.path().filename().string());
    Png png = readPng(e.path());
    ++images;
    EXPECT_EQ(png.count(kClearRgba[0], kClearRgba[1], kClearRgba[2]), 0) << "magenta in an image for people";
    std::string name = e.path().filename().string();
    bool dimmed = name.find("_cracks.png") != std::string::npos;  // crack images dim the frame to a third
    if (!dimmed) EXPECT_GT(png.count(kSkyRgba[0], kSkyRgba[1], kSkyRgba[2]), 0) << "sky where the truth has none";
  }
  EXPECT_GT(images, 0);
}

// Images are drawn after every timed and measured frame: the timing frames' counters and every
// measured value are identical with and without them.
TEST_F(ImageRun, ImagesLeaveTimingCountersAndMeasurementsAlone) {
  fs::path off = freshDir("lodbench_images_off_" + std::to_string(getpid()));
  RunTotals totalsOff = runSweep(smallConfig(false), {off.string(), false, false});
  ASSERT_EQ(totalsOn_.ok, 2);
  ASSERT_EQ(totalsOff.ok, 2);
  EXPECT_TRUE(fs::is_empty(off / "images"));
  const std::set<std::string> timed = {"gpu_ms", "cpu_ms", "fps", "cpu_harness_ms"};
  for (auto& e : fs::directory_iterator(off / "cases")) {
    SCOPED_TRACE(e.path().filename().string());
    json a = readJson(e.path());
    json b = readJson(on_ / "cases" / e.path().filename());
    EXPECT_TRUE(a["images"].empty());
    EXPECT_FALSE(b["images"].empty());
    ASSERT_EQ(a["frames"].size(), b["frames"].size());
    int compared = 0;
    for (size_t i = 0; i < a["frames"].size(); ++i) {
      const json &fa = a["frames"][i], &fb = b["frames"][i];
      for (const char* k : {"patches", "tes_invocations", "clip_invocations", "clip_primitives", "fragment_invocations",
                            "ia_vertices", "vs_invocations"})
        EXPECT_EQ(fa.value(k, json()), fb.value(k, json())) << "frame " << i << " " << k;
      for (auto& [k, v] : fa.items()) {
        if (timed.count(k) || k.find("_ms") != std::string::npos) continue;
        EXPECT_EQ(v, fb.value(k, json())) << "frame " << i << " " << k;
        ++compared;
      }
    }
    EXPECT_GT(compared, 0);
  }
}
