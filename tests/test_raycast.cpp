// The ray-cast ground truth (harness/metrics/raycast.h) on the CPU: against the independent
// polyline ray cast that validates the error pass (tests/test_error_validation.cpp), against a
// brute-force intersection of every cell (the max-mipmap may skip nothing it must not), and its
// persistent cache (harness/replay/measure.h ReferenceCache).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <thread>

#include "camera/camera_matrices.h"
#include "metrics/raycast.h"
#include "render/renderer.h"
#include "replay/measure.h"
#include "terrain/heightfield.h"

using namespace lb;

namespace {

constexpr float kExtent = 1000;
constexpr int kSamples = 257;
constexpr float kA = 2e-3f;  // h = kA (x - 500)^2, the trough of test_error_validation.cpp

Heightfield trough() {
  Heightfield hf;
  hf.width = hf.height = kSamples;
  hf.extent = kExtent;
  hf.h.resize(size_t(kSamples) * kSamples);
  for (int z = 0; z < kSamples; ++z)
    for (int x = 0; x < kSamples; ++x) {
      float wx = kExtent * float(x) / float(kSamples - 1) - 500.0f;
      hf.h[size_t(z) * kSamples + size_t(x)] = kA * wx * wx;
    }
  hf.updateRange();
  return hf;
}

// test_error_validation.cpp's Polyline with a knot at every texel column: the heights depend on x
// only, so the bilinear surface is exactly this piecewise-linear s(x). Convex, eye above: the first
// crossing found by testing every segment is the visible one.
struct Polyline {
  std::vector<double> x, y;
  bool hit(glm::dvec3 o, glm::dvec3 d, glm::dvec3& p) const {
    double best = INFINITY;
    for (size_t m = 0; m + 1 < x.size(); ++m) {
      double slope = (y[m + 1] - y[m]) / (x[m + 1] - x[m]);
      double denom = d.y - slope * d.x;
      if (denom == 0) continue;
      double t = (y[m] + slope * (o.x - x[m]) - o.y) / denom;
      double px = o.x + t * d.x, pz = o.z + t * d.z;
      if (t > 0 && t < best && px >= x[m] && px <= x[m + 1] && pz >= 0 && pz <= kExtent) best = t;
    }
    if (!std::isfinite(best)) return false;
    p = o + best * d;
    return true;
  }
};

Heightfield procedural(int size, uint32_t seed) {
  TerrainSpec s;
  s.size = size;
  s.seed = seed;
  return makeProcedural(s);
}

CameraPose pose(glm::vec3 eye, glm::vec3 target, float fov = 60) {
  CameraPose p;
  p.eye = eye;
  p.target = target;
  p.fovDeg = fov;
  return p;
}

glm::dmat4 inverseViewProj(const CameraPose& p, int w, int h, float extent) {
  CameraMatrices cam = cameraMatrices(p, float(w) / float(h), extent);
  return glm::inverse(glm::dmat4(cam.proj) * glm::dmat4(cam.view));
}

// First crossing of the surface by marching the ray in steps of 1/20 unit (a quarter of a percent
// of a cell) through the terrain's bounding box, refined by bisection: no mipmap, no quadratic.
// It can only miss a crossing pair closer together than a step (the ray grazing a crest), which
// would show as a coverage disagreement.
bool bruteForceHit(const Heightfield& hf, glm::dvec3 o, glm::dvec3 d, double& tHit) {
  double ta = 0, tb = 1;
  const double lo[3] = {0, hf.minHeight, 0}, hi[3] = {hf.extent, hf.maxHeight, hf.extent};
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    ta = std::max(ta, std::min(a, b));
    tb = std::min(tb, std::max(a, b));
  }
  if (ta > tb) return false;
  // Heightfield::sample's bilinear (lerp of lerps), in double so that only the march is compared.
  auto f = [&](double t) {
    glm::dvec3 p = o + t * d;
    double tx = p.x / hf.extent * (hf.width - 1), tz = p.z / hf.extent * (hf.height - 1);
    int x0 = std::min(int(std::floor(tx)), hf.width - 2), z0 = std::min(int(std::floor(tz)), hf.height - 2);
    double fx = tx - x0, fz = tz - z0;
    auto mix = [](double a, double b, double w) { return a * (1 - w) + b * w; };
    return p.y - mix(mix(hf.at(x0, z0), hf.at(x0 + 1, z0), fx), mix(hf.at(x0, z0 + 1), hf.at(x0 + 1, z0 + 1), fx), fz);
  };
  const int steps = int(std::ceil((tb - ta) * glm::length(d) / 0.05)) + 1;
  double fPrev = f(ta);
  for (int i = 1; i <= steps; ++i) {
    double t = ta + (tb - ta) * double(i) / steps;
    double fv = f(t);
    if ((fv <= 0) != (fPrev <= 0)) {
      double l = ta + (tb - ta) * double(i - 1) / steps, h = t;
      for (int k = 0; k < 60; ++k) {
        double mid = 0.5 * (l + h);
        ((f(mid) <= 0) == (fPrev <= 0) ? l : h) = mid;
      }
      tHit = 0.5 * (l + h);
      return true;
    }
    fPrev = fv;
  }
  return false;
}

}  // namespace

TEST(Raycast, MatchesThePolylineRayCastOfTheErrorValidation) {
  const Heightfield hf = trough();
  Polyline s;
  for (int k = 0; k < kSamples; ++k) {
    s.x.push_back(kExtent * double(k) / double(kSamples - 1));
    s.y.push_back(hf.at(k, 0));
  }
  const int w = 320, h = 180;
  const CameraPose p = pose({300, 400, -200}, {500, 100, 500});  // test_error_validation's camera
  const glm::dmat4 inv = inverseViewProj(p, w, h, kExtent);
  const MaxMipmap mip = buildMaxMipmap(hf);
  std::vector<float> dist;
  RgbaImage img = raycastImage(hf, p, w, h, &dist, 2);
  int compared = 0, coverage = 0;
  double worstPos = 0, worstDist = 0;
  for (int py = 0; py < h; py += 3)
    for (int px = 0; px < w; px += 3) {
      glm::dvec3 o, d, q(0);
      pixelRay(inv, px, py, w, h, o, d);
      bool cpu = s.hit(o, d, q);
      RayHit r = castRay(hf, mip, o, d, 0, 1);
      float rd = dist[size_t(py) * w + size_t(px)];
      if (cpu != r.hit) {
        ++coverage;  // only a ray grazing the terrain's border may disagree
        continue;
      }
      EXPECT_EQ(isClear(img, px, py), !cpu) << px << "," << py;
      if (!cpu) continue;
      worstPos = std::max(worstPos, glm::length(r.pos - q));
      double eyeDist = glm::length(q - glm::dvec3(p.eye));
      worstDist = std::max(worstDist, std::abs(double(rd) - eyeDist) / eyeDist);
      ++compared;
    }
  std::printf(
      "[raycast] %d rays vs polyline: worst hit distance %.2e units, worst relative depth %.2e, %d coverage "
      "disagreements\n",
      compared, worstPos, worstDist, coverage);
  EXPECT_GT(compared, 2000);
  // Both solve the same linear pieces in double: 1e-6 units on a 1000-unit terrain is rounding only.
  EXPECT_LT(worstPos, 1e-6);
  // The per-pixel distance is stored as float: relative 1e-6 covers its rounding.
  EXPECT_LT(worstDist, 1e-6);
  EXPECT_LE(coverage, 2);
}

TEST(Raycast, MaxMipmapFindsTheFirstHitOfABruteForceMarch) {
  const Heightfield hf = procedural(65, 3);
  const MaxMipmap mip = buildMaxMipmap(hf);
  ASSERT_EQ(mip.levels.back().w, 1);
  ASSERT_EQ(mip.levels.back().max[0], hf.maxHeight);
  const int w = 48, h = 27;
  // Grazing, looking across the ridges: occlusion matters, and rays go under and out of the terrain.
  for (const CameraPose& p : {pose({-100, 130, 300}, {900, 40, 600}), pose({500, 800, -300}, {500, 0, 500})}) {
    const glm::dmat4 inv = inverseViewProj(p, w, h, hf.extent);
    int hits = 0, misses = 0;
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        glm::dvec3 o, d;
        pixelRay(inv, px, py, w, h, o, d);
        double tb = 0;
        bool brute = bruteForceHit(hf, o, d, tb);
        RayHit r = castRay(hf, mip, o, d, 0, 1);
        ASSERT_EQ(r.hit, brute) << "pixel " << px << "," << py;
        if (!r.hit) {
          ++misses;
          continue;
        }
        ++hits;
        // Both in double: 1e-9 of the near-to-far span is 4e-6 units, rounding at grazing angles.
        EXPECT_NEAR(r.t, tb, 1e-9) << "pixel " << px << "," << py;
        EXPECT_NEAR(r.pos.y, hf.sample(float(r.pos.x), float(r.pos.z)), 1e-3) << "hit on the surface";
      }
    EXPECT_GT(hits, 0);
    EXPECT_GT(misses, 0);
  }
}

TEST(Raycast, TimePerImage) {
  // Reported, not asserted: the figure the docs quote (320x180 on this machine, all cores).
  const Heightfield hf = procedural(513, 1);
  const CameraPose p = pose({-200, 600, -200}, {500, 0, 500});
  auto t0 = std::chrono::steady_clock::now();
  RgbaImage img = raycastImage(hf, p, 320, 180);
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[raycast] 320x180 on a 513^2 terrain: %.1f ms (%u threads)\n", ms, std::thread::hardware_concurrency());
  long terrain = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) terrain += !isClear(img, x, y);
  EXPECT_GT(terrain, 0);
}

TEST(Raycast, CacheWritesEachImageAndReadsItBackInANewProcess) {
  const auto dir = std::filesystem::temp_directory_path() / ("lodbench_truth_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const Heightfield hf = procedural(65, 3);
  const CameraPose a = pose({500, 800, -300}, {500, 0, 500}), b = pose({500, 801, -300}, {500, 0, 500});
  RgbaImage first;
  {
    ReferenceCache cache(dir.string());
    first = cache.image(hf, "proc65s3", 96, 54, a);
    EXPECT_TRUE(std::filesystem::exists(cache.file(hf, "proc65s3", 96, 54, a))) << "written as soon as made";
    cache.image(hf, "proc65s3", 96, 54, a);  // in memory
    EXPECT_EQ(cache.rayCasts(), 1);
    EXPECT_EQ(cache.loaded(), 0);
  }
  ReferenceCache resumed(dir.string());
  EXPECT_EQ(resumed.image(hf, "proc65s3", 96, 54, a).px, first.px);
  EXPECT_EQ(resumed.loaded(), 1);
  EXPECT_EQ(resumed.rayCasts(), 0);
  // Everything that defines the image is in the key: pose, resolution, and the heights themselves.
  Heightfield raised = hf;
  raised.h[100] += 1.0f;
  std::set<std::string> files = {resumed.file(hf, "proc65s3", 96, 54, a), resumed.file(hf, "proc65s3", 96, 54, b),
                                 resumed.file(hf, "proc65s3", 96, 55, a), resumed.file(raised, "proc65s3", 96, 54, a)};
  EXPECT_EQ(files.size(), 4u);
  resumed.image(raised, "proc65s3", 96, 54, a);
  EXPECT_EQ(resumed.rayCasts(), 1);
  EXPECT_EQ(ReferenceCache().file(hf, "proc65s3", 96, 54, a), "") << "no directory: memory only";
  std::filesystem::remove_all(dir);
}
