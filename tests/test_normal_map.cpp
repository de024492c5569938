// Shaded frames take their normals from a per-terrain normal map (terrain/normal_map.h),
// one filtered fetch per pixel, instead of four bilinear height lookups per pixel. The map's texels
// are the old central-difference gradients, so the filtered gradient is the old one up to rounding:
// on the CPU (exactly stated below) and on the GPU against the old shader, kept as the test-only
// variant RenderSettings::testHeightNormals, with identical counters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <utility>

#include "dem_crop.h"
#include "gpu_fixture.h"
#include "metrics/image_metrics.h"
#include "render/image_io.h"
#include "terrain/heightfield.h"
#include "terrain/normal_map.h"

using namespace lb;

namespace {

// The old per-pixel normal (common.glsl terrainNormal), on the CPU.
glm::vec3 heightNormal(const Heightfield& hf, float x, float z) {
  const float tx = hf.extent / float(hf.width - 1), tz = hf.extent / float(hf.height - 1);
  float hl = hf.sample(x - tx, z), hr = hf.sample(x + tx, z);
  float hd = hf.sample(x, z - tz), hu = hf.sample(x, z + tz);
  return glm::normalize(glm::vec3((hl - hr) / (2.0f * tx), 1.0f, (hd - hu) / (2.0f * tz)));
}

Heightfield quickTerrain() {  // configs/quick.json's terrain
  TerrainSpec s;
  s.size = 513;
  s.seed = 1;
  s.extent = 1000;
  s.heightScale = 120;
  return makeProcedural(s);
}

}  // namespace

TEST(NormalMap, HalfConversionRoundTripsEveryFiniteHalfAndRoundsToNearest) {
  for (uint32_t h = 0; h < 0x10000; ++h) {
    if (((h >> 10) & 0x1f) == 0x1f) continue;  // inf and NaN are never stored
    ASSERT_EQ(floatToHalf(halfToFloat(uint16_t(h))), h) << h;
    // The value by the definition of binary16, in double (every half is exact there): a round trip
    // through a wrong pair of conversions would still pass the line above.
    const int e = int(h >> 10 & 0x1f), m = int(h & 0x3ff);
    const double v = (h & 0x8000 ? -1.0 : 1.0) * (e == 0 ? std::ldexp(m, -24) : std::ldexp(1024 + m, e - 25));
    const float f = halfToFloat(uint16_t(h)), want = float(v);
    ASSERT_EQ(std::memcmp(&f, &want, sizeof f), 0) << h << ": " << f << " against " << want;
  }
  EXPECT_EQ(floatToHalf(1.0f), 0x3c00);
  // Between two neighbouring halves: below the midpoint down, above it up, on it to the even one.
  const float a = halfToFloat(0x3c00), b = halfToFloat(0x3c01), c = halfToFloat(0x3c02);
  EXPECT_EQ(floatToHalf(a + (b - a) * 0.49f), 0x3c00);
  EXPECT_EQ(floatToHalf(a + (b - a) * 0.51f), 0x3c01);
  EXPECT_EQ(floatToHalf(0.5f * (a + b)), 0x3c00);
  EXPECT_EQ(floatToHalf(0.5f * (b + c)), 0x3c02);
  EXPECT_EQ(floatToHalf(1e9f), 0x7bff);  // clamped to the largest finite half, 65504
  EXPECT_EQ(floatToHalf(-1e9f), 0xfbff);
  EXPECT_EQ(floatToHalf(halfToFloat(0x0001) * 0.49f), 0x0000);  // below half the smallest subnormal
}

// A plane's gradient is the same at every texel (away from the clamped border), so its normal map
// gives the plane's normal everywhere inside, whatever the filter weights.
// computeNormalMap converts eight texels at a time where the processor has F16C: every level's
// texels must be the one-at-a-time conversion's, bit for bit, on what a conversion gets wrong:
// gradients past the half range (clamped), below its normal range (subnormal halves and zeros of
// both signs), ties, and odd and even, square and non-square sizes (a coarse level's last row or
// column then means three fine ones, which stay one at a time).
TEST(NormalMap, LanesGiveTheSameTexelsAsOneAtATime) {
  if (!normalMapLanes()) GTEST_SKIP() << "this processor has no F16C: computeNormalMap takes no lanes here";
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int compared = 0;
  for (auto [w, h] : {std::pair{37, 23}, {64, 64}, {65, 3}, {2, 9}, {19, 2}, {130, 67}}) {
    Heightfield hf;
    hf.width = w;
    hf.height = h;
    hf.extent = 1.0f;
    hf.h.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < hf.h.size(); ++i) {
      switch (i % 5) {
        case 0:
          hf.h[i] = 1e4f * unit(rng);
          break;  // steep: past 65504 once divided by the spacing
        case 1:
          hf.h[i] = 1e-9f * unit(rng);
          break;  // subnormal gradients
        case 2:
          hf.h[i] = 0.0f;
          break;
        case 3:
          hf.h[i] = -0.0f;
          break;
        default:
          hf.h[i] = float(int(64 * unit(rng))) / 4096.0f;  // coarse steps: ties in the means
      }
    }
    hf.updateRange();
    const NormalMap one = computeNormalMap(hf, false), lanes = computeNormalMap(hf, true);
    ASSERT_EQ(one.levels(), lanes.levels());
    for (int k = 0; k < one.levels(); ++k) {
      EXPECT_EQ(one.levelTexels(k), lanes.levelTexels(k)) << w << " x " << h << ", level " << k;
      compared += int(one.levelTexels(k).size());
    }
  }
  EXPECT_GT(compared, 30000);
}

TEST(NormalMap, PlaneGivesItsNormalInside) {
  Heightfield hf;
  hf.width = hf.height = 65;
  hf.extent = 640;
  const float a = 0.3f, b = -1.7f;
  for (int z = 0; z < hf.height; ++z)
    for (int x = 0; x < hf.width; ++x) hf.h.push_back(a * float(x) * 10.0f + b * float(z) * 10.0f);
  hf.updateRange();
  const NormalMap nm = computeNormalMap(hf);
  const glm::vec3 expected = glm::normalize(glm::vec3(-a, 1.0f, -b));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> inside(10.0f, 630.0f);  // one texel (10 units) from the border
  for (int i = 0; i < 1000; ++i) {
    glm::vec3 n = sampleNormalMap(nm, hf.extent, inside(rng), inside(rng));
    ASSERT_LT(glm::length(n - expected), 1e-3f);  // float16 keeps 11 bits of -a and -b
  }
}

// The design claim of terrain/normal_map.h: the bilinear interpolation of the texel gradients IS
// the old per-pixel central difference of the bilinear heights, border clamping included. Left:
// float16 rounding of the gradients (relative 2^-11, so a normal component moves by < 2.5e-4) and
// float arithmetic. A planted defect (one texel's gradient negated) shows around that texel only.
TEST(NormalMap, FilteredGradientEqualsThePerPixelCentralDifference) {
  const Heightfield& hf = lbtest::testTerrain();
  NormalMap nm = computeNormalMap(hf);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> any(0.0f, hf.extent);
  float worst = 0;
  for (int i = 0; i < 20000; ++i) {
    float x = any(rng), z = any(rng);
    if (i < 200) x = i % 2 ? 0.0f : hf.extent;  // the clamped border too
    worst = std::max(worst, glm::length(sampleNormalMap(nm, hf.extent, x, z) - heightNormal(hf, x, z)));
  }
  std::printf("[normal map] largest |n_map - n_per_pixel| over 20000 points: %.2e\n", worst);
  EXPECT_LT(worst, 1e-3f);
  const int tx = 40, tz = 70;
  const float texel = hf.extent / float(hf.width - 1);
  size_t k = (size_t(tz) * size_t(hf.width) + size_t(tx)) * 2;
  const float gx = halfToFloat(nm.texels[k]), gz = halfToFloat(nm.texels[k + 1]);
  ASSERT_GT(std::fabs(gx) + std::fabs(gz), 0.05f) << "pick a sloped texel, or the plant changes nothing";
  nm.texels[k] = floatToHalf(-gx + 1.0f);
  nm.texels[k + 1] = floatToHalf(-gz + 1.0f);
  EXPECT_GT(glm::length(sampleNormalMap(nm, hf.extent, tx * texel + 0.3f * texel, tz * texel) -
                        heightNormal(hf, tx * texel + 0.3f * texel, tz * texel)),
            0.1f);
  EXPECT_LT(glm::length(sampleNormalMap(nm, hf.extent, (tx + 1.5f) * texel, tz * texel) -
                        heightNormal(hf, (tx + 1.5f) * texel, tz * texel)),
            1e-3f);
}

// ---- GPU: the new shader against the old one, same geometry.

namespace {

// Tolerance of new vs old shaded frames. The normal moves by < 2.5e-4 from float16 texels (the CPU
// test above), plus the sampler's sub-texel weight precision (8 bits on lavapipe: a gradient off by
// at most 1/512 of its change across a texel); diffuse light and the slope blend map that to well
// under one RGBA8 level, so a pixel moves by one level only where its value sits near a rounding
// boundary. Measured on lavapipe: max 1 level, PSNR 76-86 dB on every frame below. Allowed: 2 levels
// (a sampler with coarser weights on the steepest cells) and 65 dB (RMS 0.14 levels: at most ~3% of
// channels moving by one level), well below what any LOD difference between schemes produces.
constexpr int kMaxChannelDiff = 2;
constexpr double kMinPsnrDb = 65.0;

struct Diff {
  int maxChannel = 0;
  double psnr = 0;
};

Diff diffImages(const RgbaImage& a, const RgbaImage& b) {
  Diff d;
  for (size_t i = 0; i < a.px.size(); ++i) d.maxChannel = std::max(d.maxChannel, std::abs(int(a.px[i]) - int(b.px[i])));
  d.psnr = compareImages(a, b).psnrDb;
  return d;
}

void expectSameStats(const PipelineStats& a, const PipelineStats& b, const std::string& what) {
  EXPECT_EQ(a.iaVertices, b.iaVertices) << what;
  EXPECT_EQ(a.iaPrimitives, b.iaPrimitives) << what;
  EXPECT_EQ(a.vsInvocations, b.vsInvocations) << what;
  EXPECT_EQ(a.tcsPatches, b.tcsPatches) << what;
  EXPECT_EQ(a.tesInvocations, b.tesInvocations) << what;
  EXPECT_EQ(a.clipInvocations, b.clipInvocations) << what;
  EXPECT_EQ(a.clipPrimitives, b.clipPrimitives) << what;
  EXPECT_EQ(a.fsInvocations, b.fsInvocations) << what;
  EXPECT_GT(a.fsInvocations, 0u) << what << ": nothing drawn proves nothing";
}

// The old shader (per-pixel normals from four height lookups) and the new one, uniform at its
// defaults. Made once per terrain and reused across frames: the per-terrain set-up (normal map,
// patch bounds) dominates this test under ASan.
struct OldNew {
  Renderer oldR, newR;
  int w, h;
  OldNew(const Heightfield& hf, int width, int height, int grid)
      : oldR(lbtest::gpu(), hf, oldSettings(width, height, grid)),
        newR(lbtest::gpu(), hf, levelZeroSettings(width, height, grid)),
        w(width),
        h(height) {
    oldR.setScheme(*findScheme("uniform"), {});
    newR.setScheme(*findScheme("uniform"), {});
  }
  // The map's level 0, which stands for the per-pixel normal (its coarser levels filter on purpose).
  static RenderSettings levelZeroSettings(int width, int height, int grid) {
    RenderSettings s{width, height, grid};
    s.testMipZeroShading = true;
    return s;
  }
  static RenderSettings oldSettings(int width, int height, int grid) {
    RenderSettings s{width, height, grid};
    s.testHeightNormals = true;
    return s;
  }
};

// Renders `pose` with the old and the new shader, asserts the tolerance and identical counters and
// triangle histograms; writes old/new/difference x32 PNGs to $LODBENCH_NORMAL_MAP_PNGS/<tag>_*.png
// when that names a directory.
Diff compareOldNew(OldNew& r, const CameraPose& pose, const std::string& tag) {
  Renderer &oldR = r.oldR, &newR = r.newR;
  const int w = r.w, h = r.h;
  FrameResult fo, fn;
  RgbaImage o{w, h, oldR.renderImage(pose, pose, RenderMode::Shaded, &fo)};
  RgbaImage n{w, h, newR.renderImage(pose, pose, RenderMode::Shaded, &fn)};
  expectSameStats(fo.stats, fn.stats, tag);
  TriangleHistogram ho = oldR.measureHistogram(pose, pose), hn = newR.measureHistogram(pose, pose);
  EXPECT_EQ(ho.bins, hn.bins) << tag;
  EXPECT_EQ(ho.total(), hn.total()) << tag;
  Diff d = diffImages(o, n);
  EXPECT_LE(d.maxChannel, kMaxChannelDiff) << tag;
  EXPECT_GE(d.psnr, kMinPsnrDb) << tag;
  std::printf("[normal map] %s: new vs old shading max channel difference %d, PSNR %.1f dB\n", tag.c_str(),
              d.maxChannel, d.psnr);
  if (const char* dir = std::getenv("LODBENCH_NORMAL_MAP_PNGS")) {
    std::vector<uint8_t> amp(o.px.size());
    for (size_t i = 0; i < amp.size(); ++i)
      amp[i] = i % 4 == 3 ? 255 : uint8_t(std::min(255, 32 * std::abs(int(o.px[i]) - int(n.px[i]))));
    writePng(std::string(dir) + "/" + tag + "_old.png", w, h, o.px);
    writePng(std::string(dir) + "/" + tag + "_new.png", w, h, n.px);
    writePng(std::string(dir) + "/" + tag + "_diff32.png", w, h, amp);
  }
  return d;
}

}  // namespace

class NormalMapPaths : public lbtest::GpuTest, public ::testing::WithParamInterface<const char*> {};

// quick.json's terrain at 320x180 on a 32 x 32 grid, every 90th frame of each shipped path.
TEST_P(NormalMapPaths, NewShadingWithinToleranceOfPerPixelNormalsWithIdenticalCounters) {
  const Heightfield hf = quickTerrain();
  const char* name = GetParam();
  CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
  OldNew r(hf, 320, 180, 32);
  int frames = 0;
  for (int f = 0; f < frameCount(path, 30); f += 90, ++frames)
    compareOldNew(r, samplePose(path, 30, f, hf), std::string(name) + "_" + std::to_string(f));
  EXPECT_GE(frames, 3);
}

INSTANTIATE_TEST_SUITE_P(ShippedPaths, NormalMapPaths, ::testing::Values("flyover", "lowalt", "horizon"));

class NormalMapFrames : public lbtest::GpuTest {};

// The frames docs/ shows (640x360): flyover frame 240 over quick.json's terrain, and the SRTM tile
// N44W072 (the committed crop, tests/dem_crop.h).
TEST_F(NormalMapFrames, FlyoverAndDemAt640x360) {
  const Heightfield hf = quickTerrain();
  CameraPath flyover = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv");
  {
    OldNew r(hf, 640, 360, 32);
    compareOldNew(r, samplePose(flyover, 30, 240, hf), "flyover_240");
  }
  const Heightfield dem = loadHeightfield(lbtest::demCrop());
  OldNew r(dem, 640, 360, 32);
  compareOldNew(r, samplePose(flyover, 30, 240, dem), "dem_flyover_240");
}
