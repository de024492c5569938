// GPU reductions (metrics/gpu_reduce.h) against the CPU's statistics: rendered frames of shipped
// schemes against the ray-cast truth, planted holes and missing terrain, and error maps with known values.
#include <cmath>
#include <cstdio>

#include "gpu_fixture.h"
#include "metrics/coverage.h"
#include "metrics/gpu_reduce.h"
#include "metrics/image_metrics.h"
#include "metrics/raycast.h"
#include "shaders/reduce_params.h"
#include "stats.h"

using namespace lb;
using lbtest::gpu;

namespace {

const int kW = 192, kH = 108;

RgbaImage solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4, 255)};
  for (size_t i = 0; i < img.px.size(); i += 4) {
    img.px[i] = r;
    img.px[i + 1] = g;
    img.px[i + 2] = b;
  }
  return img;
}

void setClear(RgbaImage& img, int x, int y) {
  uint8_t* p = &img.px[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  p[0] = 255;
  p[1] = 0;
  p[2] = 255;
}

// The counts compareImages does not make, pixel by pixel on the CPU (the rules of gpu_reduce.h).
struct Counts {
  long missing = 0, extra = 0, candidates = 0;
};
Counts cpuCounts(const RgbaImage& a, const RgbaImage& b, int reach = 3) {
  auto terrain = [&](int x, int y) { return x >= 0 && y >= 0 && x < a.width && y < a.height && !isClear(a, x, y); };
  auto enclosed = [&](int x, int y, int dx, int dy) {
    bool before = false, after = false;
    for (int s = 1; s <= reach; ++s) {
      before = before || terrain(x - dx * s, y - dy * s);
      after = after || terrain(x + dx * s, y + dy * s);
    }
    return before && after;
  };
  Counts c;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool ca = isClear(a, x, y), cb = isClear(b, x, y);
      c.extra += !ca && cb;
      c.missing += ca && !cb;
      c.candidates += ca && !cb && (enclosed(x, y, 1, 0) || enclosed(x, y, 0, 1));
    }
  return c;
}

// Returns the GPU's SSIM minus the CPU's.
double expectCompareAsCpu(GpuReduce& r, const RgbaImage& a, const RgbaImage& b) {
  const ImageError cpu = compareImages(a, b);
  const GpuImageStats g = r.compare(r.upload(a), r.upload(b));
  // Exactly equal: the same integer sums and histogram ranks through the same formulas.
  EXPECT_EQ(g.e.psnrDb, cpu.psnrDb);
  EXPECT_EQ(g.e.meanAbsDiff, cpu.meanAbsDiff);
  EXPECT_EQ(g.e.fractionOver, cpu.fractionOver);
  EXPECT_EQ(g.e.p99AbsDiff, cpu.p99AbsDiff);
  EXPECT_EQ(g.e.changedPixels, cpu.changedPixels);
  EXPECT_NEAR(g.e.ssim, cpu.ssim, r.float64() ? 1e-12 : 1e-4);
  const Counts c = cpuCounts(a, b);
  EXPECT_EQ(g.coverageMissing, c.missing);
  EXPECT_EQ(g.coverageExtra, c.extra);
  EXPECT_EQ(g.crackCandidates, c.candidates);
  EXPECT_EQ(g.truthTerrain, coverageError(a, b).truthTerrain);  // metrics/coverage.h, the CPU path's
  EXPECT_EQ(g.coverageMissing, coverageError(a, b).missing);
  if (g.crackCandidates == 0) {
    EXPECT_EQ(crackPixels(a, b), 0);
  }
  return g.e.ssim - cpu.ssim;
}

void expectErrorStatsAsCpu(GpuReduce& r, const std::vector<float>& map) {
  std::vector<double> e;
  for (float v : map)
    if (v >= 0) e.push_back(v);
  const Summary cpu = summarize(e);
  const GpuErrorStats g = r.errorStats(r.upload(map));
  ASSERT_EQ(g.count, long(e.size()));
  EXPECT_EQ(g.max, cpu.max);
  EXPECT_LE(std::abs(g.mean - cpu.mean), 1e-6 * cpu.mean);
  // The fine histogram's resolution (gpu_reduce.h): 2^-10 of the value.
  EXPECT_LE(std::abs(g.p95 - cpu.p95), cpu.p95 / 1024 * (1 + 1e-9)) << "CPU p95 " << cpu.p95;
}

struct RenderedFrame {
  RgbaImage shaded, truth;
  std::vector<float> error;
};

// Shipped schemes of the three draw paths on two shipped paths, at a small size (rendered once).
const std::vector<RenderedFrame>& renderedFrames() {
  static const std::vector<RenderedFrame> frames = [] {
    std::vector<RenderedFrame> out;
    const Heightfield& hf = lbtest::testTerrain();
    for (const char* name : {"sphere", "cdlod", "cbt"}) {
      Renderer r(gpu(), hf, {kW, kH, 16});
      r.setScheme(*findScheme(name), {});
      for (const char* path : {"flyover", "lowalt"}) {
        CameraPath p = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + path + ".csv");
        CameraPose pose = samplePose(p, 30, frameCount(p, 30) / 2, hf);
        RenderedFrame f;
        f.shaded = {kW, kH, r.renderImage(pose, pose, RenderMode::Shaded)};
        f.truth = raycastImage(hf, pose, kW, kH);
        f.error = r.renderErrorMap(pose, pose);
        out.push_back(std::move(f));
      }
    }
    return out;
  }();
  return frames;
}

}  // namespace

class GpuReduceTest : public lbtest::GpuTest {};

TEST_F(GpuReduceTest, RenderedFramesMatchTheCpu) {
  GpuReduce r(gpu(), kW, kH), single(gpu(), kW, kH, false);
  double worstFloat = 0;
  for (const RenderedFrame& f : renderedFrames()) {
    expectCompareAsCpu(r, f.shaded, f.truth);
    worstFloat = std::max(worstFloat, std::abs(expectCompareAsCpu(single, f.shaded, f.truth)));
    expectErrorStatsAsCpu(r, f.error);
    EXPECT_GT(r.lastGpuMs(), 0.0);
  }
  std::printf("[gpu_reduce] SSIM in %s; in float (mean shift %g): largest |GPU - CPU| %.3g over 6 frames\n",
              r.float64() ? "double" : "float", LB_SSIM_SHIFT, worstFloat);
}

TEST_F(GpuReduceTest, IdenticalImagesReadIdentical) {
  const RenderedFrame& f = renderedFrames().front();
  for (bool allow64 : {true, false}) {
    GpuReduce r(gpu(), kW, kH, allow64);
    const GpuImageStats g = r.compare(r.upload(f.truth), r.upload(f.truth));
    EXPECT_EQ(g.e.psnrDb, kPsnrIdentical);
    // Exact per window in real arithmetic; float rounds (or fuses) numerator and denominator apart.
    EXPECT_NEAR(g.e.ssim, 1.0, r.float64() ? 1e-15 : 1e-6);
    EXPECT_EQ(g.e.meanAbsDiff + g.e.fractionOver + g.e.p99AbsDiff, 0.0);
    EXPECT_EQ(g.e.changedPixels + g.coverageMissing + g.coverageExtra + g.crackCandidates, 0);
  }
}

TEST_F(GpuReduceTest, PlantedHoleIsACrackCandidate) {
  RgbaImage truth = renderedFrames().front().truth, holed = truth;
  // The first pixel with terrain 4 pixels around it every way: a 5-pixel hole there is a crack.
  auto terrainAround = [&](int x, int y) {
    for (int dy = -4; dy <= 4; ++dy)
      for (int dx = -4; dx <= 4; ++dx)
        if (isClear(truth, x + dx, y + dy)) return false;
    return true;
  };
  int hx = -1, hy = -1;
  for (int y = 4; y < kH - 4 && hx < 0; ++y)
    for (int x = 6; x < kW - 6 && hx < 0; ++x)
      if (terrainAround(x, y) && terrainAround(x - 2, y) && terrainAround(x + 2, y)) hx = x, hy = y;
  ASSERT_GE(hx, 0) << "no terrain in the test frame";
  for (int x = hx - 2; x <= hx + 2; ++x) setClear(holed, x, hy);
  GpuReduce r(gpu(), kW, kH);
  const GpuImageStats g = r.compare(r.upload(holed), r.upload(truth));
  EXPECT_EQ(g.crackCandidates, 5);
  EXPECT_EQ(g.coverageMissing, 5);
  EXPECT_EQ(crackPixels(holed, truth), 5);
  // A notch open to the sky is a candidate by the local rule alone; crackPixels' flood fill drops it.
  RgbaImage sky = solid(40, 30, 60, 90, 40), notched;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 40; ++x) setClear(sky, x, y);
  notched = sky;
  for (int y = 8; y < 10; ++y)
    for (int x = 30; x < 33; ++x) setClear(notched, x, y);
  GpuReduce small(gpu(), 40, 30);
  expectCompareAsCpu(small, notched, sky);
  EXPECT_EQ(small.compare(small.upload(notched), small.upload(sky)).crackCandidates, 6);
  EXPECT_EQ(crackPixels(notched, sky), 0);
}

TEST_F(GpuReduceTest, AllTerrainRemovedIsMissingCoverage) {
  const RgbaImage truth = renderedFrames().front().truth, none = solid(kW, kH, 255, 0, 255);
  long terrain = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) terrain += !isClear(truth, x, y);
  ASSERT_GT(terrain, 0);
  GpuReduce r(gpu(), kW, kH);
  const GpuImageStats g = r.compare(r.upload(none), r.upload(truth)),
                      swapped = r.compare(r.upload(truth), r.upload(none));
  EXPECT_EQ(g.coverageMissing, terrain);
  EXPECT_EQ(g.coverageExtra, 0);
  EXPECT_EQ(g.crackCandidates, 0);  // nothing of `a` encloses a hole
  EXPECT_EQ(swapped.coverageExtra, terrain);
  EXPECT_EQ(swapped.coverageMissing, 0);
  expectCompareAsCpu(r, none, truth);
}

// Black against white at 256x256: the squared differences add up to 1.28e10, past 32 bits.
TEST_F(GpuReduceTest, SumsPastThirtyTwoBitsStayExact) {
  GpuReduce r(gpu(), 256, 256);
  const RgbaImage black = solid(256, 256, 0, 0, 0), white = solid(256, 256, 255, 255, 255);
  expectCompareAsCpu(r, black, white);
  const GpuImageStats g = r.compare(r.upload(black), r.upload(white), 16, false);
  EXPECT_EQ(g.e.psnrDb, 0.0);
  EXPECT_EQ(g.e.meanAbsDiff, 255.0);
  EXPECT_EQ(g.e.p99AbsDiff, 255.0);
  EXPECT_TRUE(std::isnan(g.e.ssim)) << "SSIM not asked for reads NaN, not 0";
}

TEST_F(GpuReduceTest, ErrorMapsWithKnownValues) {
  GpuReduce r(gpu(), kW, kH);
  const size_t n = size_t(kW) * kH;
  const GpuErrorStats none = r.errorStats(r.upload(std::vector<float>(n, -1.0f)));
  EXPECT_EQ(none.count, 0);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.p95) && std::isnan(none.max));
  // A ramp with every 7th pixel off the terrain, -0 (counted, as v >= 0 counts it) and zeros.
  std::vector<float> ramp(n);
  for (size_t i = 0; i < n; ++i) ramp[i] = i % 7 == 3 ? -1.0f : float(i) * 0.0137f;
  ramp[5] = -0.0f;
  expectErrorStatsAsCpu(r, ramp);
  EXPECT_EQ(r.errorStats(r.upload(ramp)).max, double(float(n - 1) * 0.0137f));
  // Values over 14 binary orders of magnitude, and one value repeated for most pixels.
  std::vector<float> spread(n), repeated(n, 0.5f);
  for (size_t i = 0; i < n; ++i) spread[i] = 1e-3f * std::pow(1.0006f, float(i % 16000));
  for (size_t i = 0; i < n / 20; ++i) repeated[i * 20] = float(i) * 0.01f;
  expectErrorStatsAsCpu(r, spread);
  expectErrorStatsAsCpu(r, repeated);
}

TEST_F(GpuReduceTest, BadSizesAreRefusedWithTheSizes) {
  EXPECT_THROW({ GpuReduce bad(gpu(), 0, 10); }, std::invalid_argument);
  GpuReduce r(gpu(), kW, kH);
  Buffer small = r.upload(std::vector<float>(10, 0.0f));
  try {
    r.errorStats(small);
    ADD_FAILURE() << "a 40-byte error map passed for 192x108";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("192x108 needs 82944"), std::string::npos) << e.what();
  }
  GpuReduce tiny(gpu(), 8, 8);
  RgbaImage img = solid(8, 8, 1, 2, 3);
  EXPECT_THROW(tiny.compare(tiny.upload(img), tiny.upload(img)), std::invalid_argument);  // SSIM needs 11x11
  EXPECT_EQ(tiny.compare(tiny.upload(img), tiny.upload(img), 16, false).e.changedPixels, 0);
}
