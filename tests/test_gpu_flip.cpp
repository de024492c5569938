// FLIP's compute passes (metrics/gpu_flip.h) against the CPU oracle (metrics/flip.h), pixel by pixel,
// on frames of every shipped path over the procedural terrain (first, middle and last) and the
// committed DEM crop (middle): the live frame of sphere against the ray-cast truth, both in device
// buffers as the GPU measurement path holds them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dem_crop.h"
#include "gpu_fixture.h"
#include "metrics/flip.h"
#include "metrics/gpu_flip.h"
#include "replay/measure_gpu.h"
#include "terrain/heightfield.h"

using namespace lb;

namespace {

// Frames 0, the middle and the last of every path (`allFrames`), or its middle only.
void everyShippedPath(const Heightfield& hf, const char* label, bool allFrames) {
  const int w = 160, h = 90;
  Renderer r(lbtest::gpu(), hf, {w, h, 16});
  r.setScheme(*findScheme("sphere"), {});
  MeasureGpu g(lbtest::gpu(), w, h);
  GpuFlip flip(lbtest::gpu(), w, h, kFlipDefaultPpd);
  double worst = 0, worstMean = 0;
  int frames = 0;
  for (const std::string& file : lbtest::shippedPathFiles()) {
    const CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
    const int n = frameCount(path, 30);
    for (int f : allFrames ? std::vector<int>{0, n / 2, n - 1} : std::vector<int>{n / 2}) {
      const CameraPose pose = samplePose(path, 30, f, hf);
      r.renderInto(pose, pose, RenderMode::Shaded, &g.shaded);
      g.castTruth(hf, pose);
      const std::vector<float> gpuMap = g.readFloats(flip.run(g.truth, g.shaded));
      const std::vector<float> cpuMap = flipMap(asSeen(g.readImage(g.truth)), asSeen(g.readImage(g.shaded)));
      ASSERT_EQ(gpuMap.size(), cpuMap.size());
      double frameWorst = 0;
      size_t at = 0;
      for (size_t i = 0; i < cpuMap.size(); ++i)
        if (double d = std::abs(double(gpuMap[i]) - cpuMap[i]); d > frameWorst) frameWorst = d, at = i;
      EXPECT_LE(frameWorst, 1e-4) << label << " " << file << " frame " << f << " pixel " << at << ": gpu " << gpuMap[at]
                                  << " cpu " << cpuMap[at];
      worst = std::max(worst, frameWorst);
      worstMean = std::max(worstMean, std::abs(flipStats(gpuMap).mean - flipStats(cpuMap).mean));
      ++frames;
    }
  }
  std::printf("[gpu flip] %s: %d frames, largest per-pixel difference %.2e, of a frame's mean %.2e\n", label, frames,
              worst, worstMean);
}

}  // namespace

class GpuFlipTest : public lbtest::GpuTest {};

TEST_F(GpuFlipTest, AgreesWithTheCpuOnEveryShippedPath) {
  everyShippedPath(lbtest::testTerrain(), "procedural", true);
}

TEST_F(GpuFlipTest, AgreesWithTheCpuOnTheDemCrop) {
  const Heightfield hf = makeHeightfield(lbtest::demCrop());
  everyShippedPath(hf, "DEM crop", false);
}
