// Pins what every scheme draws: SHA-256 of the decoded pixels of the shaded, heat-map and error
// images of every registered scheme at three poses (first, middle and last frame) of every
// shipped camera path, against tests/data/image_hashes.json. A refactor that claims to change
// no output must leave every pinned hash as it was; a change that means to alter an image regenerates
// the file with LODBENCH_UPDATE_IMAGE_HASHES=1 and says why in its commit.
// The hashes are of lavapipe's rasterisation (the CI device); another driver draws other bits.
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera/camera_path.h"
#include "config/config.h"
#include "gpu_fixture.h"
#include "render/scheme.h"
#include "schemes/registry.h"
#include "sha256.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";
const std::string kHashFile = std::string(LODBENCH_SOURCE_DIR) + "/tests/data/image_hashes.json";
constexpr int kFps = 2;

std::vector<std::string> shippedPaths() {
  return lbtest::shippedPathFiles();
}

// Frames the runner replays for a path at kFps (t = 0, 1/fps, ... up to the path's end).
int pathFrames(const std::string& file) {
  return frameCount(loadCameraPath(kConfigs + "/paths/" + file), kFps);
}

std::string pixelHash(const fs::path& png) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(png.c_str(), &w, &h, &n, 4);
  if (!data) throw std::runtime_error("cannot read " + png.string());
  Sha256 s;
  s.update(&w, sizeof w);
  s.update(&h, sizeof h);
  s.update(data, size_t(w) * size_t(h) * 4);
  stbi_image_free(data);
  return s.hex();
}

}  // namespace

// Every scheme x every shipped path; measurement on the image frames only (error images need the
// ray-cast truth of their frame). Small images keep the 3 x 3 x schemes x paths renders cheap.
TEST(ImageHashes, EverySchemeAtThreePosesOfEveryShippedPathIsUnchanged) {
  json got = json::object();
  for (const std::string& path : shippedPaths()) {
    const int n = pathFrames(path);
    const int mid = n / 2;
    json schemes = json::array();
    for (const Scheme* s : lbtest::drawableSchemes()) schemes.push_back(s->info().name);
    json cfg = {
        {"name", "hashes"},
        {"resolution", {96, 54}},
        {"grid", 4},
        {"fps", kFps},
        {"warmup_frames", 0},
        {"repetitions", 1},
        {"terrain", {{"type", "procedural"}, {"size", 65}, {"seed", 7}, {"extent", 1000}, {"height_scale", 150}}},
        {"paths", {"paths/" + path}},
        {"schemes", schemes},
        {"measure", {{"every", 0}}},
        {"images",
         {{"frames", {0, mid, n - 1}},
          {"modes", {"shaded", "heatmap", "error"}},
          {"resolution", {96, 54}},
          {"worst", false}}}};
    Config c = parseConfig(cfg.dump(), "hashes.json", kConfigs);
    fs::path dir = fs::path(::testing::TempDir()) / ("lodbench_image_hashes_" + std::to_string(getpid()));
    fs::remove_all(dir);
    RunOptions o;
    o.outDir = dir.string();
    o.progress = false;
    RunTotals t = runSweep(c, o);
    ASSERT_EQ(t.failed, 0) << path;
    size_t images = 0;
    for (const auto& e : fs::directory_iterator(dir / "images")) {
      got[path][e.path().filename().string()] = pixelHash(e.path());
      ++images;
    }
    EXPECT_EQ(images, lbtest::drawableSchemes().size() * 3 * 3) << path;
    fs::remove_all(dir);
  }
  if (std::getenv("LODBENCH_UPDATE_IMAGE_HASHES")) {
    std::ofstream(kHashFile) << got.dump(1) << "\n";
    GTEST_SKIP() << "wrote " << kHashFile;
  }
  std::ifstream f(kHashFile);
  ASSERT_TRUE(f) << "no " << kHashFile << ": run with LODBENCH_UPDATE_IMAGE_HASHES=1 once";
  json want = json::parse(f);
  int differ = 0;
  for (auto& [path, images] : want.items())
    for (auto& [name, hash] : images.items()) {
      if (!got.contains(path) || !got[path].contains(name)) {
        ADD_FAILURE() << path << " " << name << ": not drawn any more";
        ++differ;
      } else if (got[path][name] != hash) {
        ADD_FAILURE() << path << " " << name << ": pixels changed";
        ++differ;
      }
    }
  // A scheme added since the file was written has no earlier pixels to keep: its images are named,
  // not failed, and pinned the next time the file is regenerated.
  int unpinned = 0;
  for (auto& [path, images] : got.items())
    for (auto& [name, hash] : images.items()) unpinned += !want.contains(path) || !want[path].contains(name);
  if (unpinned > 0)
    std::printf("note: %d images of schemes newer than %s are not pinned (LODBENCH_UPDATE_IMAGE_HASHES=1 pins them)\n",
                unpinned, kHashFile.c_str());
  EXPECT_EQ(differ, 0);
}
