// The GPU screen-space error map (shaders/terrain.frag, LB_MODE_ERROR) checked against a CPU ray
// caster on a terrain whose tessellated surface is known exactly.
#include <algorithm>
#include <cmath>

#include "camera/camera_matrices.h"
#include "gpu_fixture.h"
#include "schemes/registry.h"

using namespace lb;
using lbtest::gpu;

namespace {

constexpr float kExtent = 1000;
constexpr int kSamples = 257;
constexpr float kA = 2e-3f;  // h = kA (x - 500)^2: a trough, 500 high at the x borders

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

glm::dvec2 toPixels(const glm::dmat4& viewProj, glm::dvec3 p, int w, int h) {
  glm::dvec4 c = viewProj * glm::dvec4(p, 1.0);
  return glm::dvec2(c.x, c.y) / c.w * glm::dvec2(0.5 * w, 0.5 * h);
}

// The heights depend on x only, so every triangle of a uniform tessellation is a plane through
// vertices at two consecutive vertex x positions with heights h(x_k), h(x_k+1): the surface is
// exactly the piecewise-linear s(x) through (x_k, h(x_k)), whatever the triangulation.
struct Polyline {
  std::vector<double> x, y;
  // First hit of the ray o + t d (t > 0) with s over [0, extent]^2, false on a miss. s is convex
  // and the eye is above it, so the ray leaves the region above s at most once: no occlusion.
  bool hit(glm::dvec3 o, glm::dvec3 d, glm::dvec3& p) const {
    double best = INFINITY;
    for (size_t m = 0; m + 1 < x.size(); ++m) {
      double slope = (y[m + 1] - y[m]) / (x[m + 1] - x[m]);
      // o.y + t d.y = y[m] + slope (o.x + t d.x - x[m])  is linear in t
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

}  // namespace

class ErrorValidation : public lbtest::GpuTest {};

TEST_F(ErrorValidation, ErrorMapMatchesCpuRayCastOnPiecewiseLinearSurface) {
  const Heightfield hf = trough();
  const int w = 320, h = 180, grid = 2, level = 3;
  Renderer r(gpu(), hf, {w, h, grid});
  r.setScheme(*findScheme("uniform"), {{"level", level}});
  CameraPose pose = lbtest::poseAt({300, 400, -200}, {500, 100, 500});
  std::vector<float> gpuErr = r.renderErrorMap(pose, pose);
  ASSERT_EQ(gpuErr.size(), size_t(w) * size_t(h));

  // Vertex x positions as terrain_quad.tese computes them (float mix of the patch corners).
  Polyline s;
  for (int i = 0; i < grid; ++i)
    for (int k = (i == 0 ? 0 : 1); k <= level; ++k) {
      float x0 = kExtent * float(i) / float(grid), x1 = kExtent * float(i + 1) / float(grid);
      float u = float(k) / float(level);
      float x = x0 * (1.0f - u) + x1 * u;
      s.x.push_back(x);
      s.y.push_back(hf.sample(x, 0.0f));
    }

  CameraMatrices cam = cameraMatrices(pose, float(w) / float(h), kExtent);
  glm::dmat4 viewProj = glm::dmat4(cam.proj) * glm::dmat4(cam.view);
  glm::dmat4 inv = glm::inverse(viewProj);
  int compared = 0, coverageDisagrees = 0;
  double sum = 0, worst = 0;
  for (int py = 3; py < h; py += 7)
    for (int px = 3; px < w; px += 7) {
      // Pixel centre in Vulkan NDC (y down), unprojected at depth 0 and 1.
      double nx = (px + 0.5) / w * 2 - 1, ny = (py + 0.5) / h * 2 - 1;
      glm::dvec4 a = inv * glm::dvec4(nx, ny, 0, 1), b = inv * glm::dvec4(nx, ny, 1, 1);
      glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
      glm::dvec3 p;
      bool cpuHit = s.hit(o, d, p);
      float g = gpuErr[size_t(py) * w + size_t(px)];
      if (!cpuHit || g < 0) {
        // Only pixel centres within a hair of the terrain's border may disagree on coverage.
        coverageDisagrees += cpuHit != (g >= 0);
        continue;
      }
      glm::dvec3 truePoint(p.x, hf.sample(float(p.x), float(p.z)), p.z);
      double expected = glm::length(toPixels(viewProj, p, w, h) - toPixels(viewProj, truePoint, w, h));
      // Tolerance: the rasterizer snaps vertices to 1/256 px, moving the sampled surface point by
      // <= 1/512 px on screen, where the error changes by far less than 1 px per px; float
      // projection of ~1000-unit coordinates adds ~1e-4 px. 1e-2 px + 1e-3 relative covers both.
      EXPECT_NEAR(g, expected, 1e-2 + 1e-3 * expected) << "pixel " << px << "," << py;
      worst = std::max(worst, std::abs(g - expected));
      sum += expected;
      ++compared;
    }
  std::printf(
      "[error validation] %d pixels compared, mean error %.3f px, worst |gpu - cpu| %.2e px, "
      "%d coverage disagreements\n",
      compared, sum / compared, worst, coverageDisagrees);
  EXPECT_GT(compared, 200);
  EXPECT_GT(sum / compared, 1.0) << "level 3 must be visibly coarse, or the comparison proves little";
  EXPECT_LE(coverageDisagrees, 3);
}

TEST_F(ErrorValidation, ReferenceDensityHasOnlyTheTriangulationTwist) {
  // Level 64 on a 2 x 2 grid puts a vertex on every texel of the 129^2 test terrain (spacing
  // 1000 / 128 both), so the only difference from the bilinear heightfield is inside each texel
  // cell: two triangles instead of a bilinear patch, at most |h00 - h10 - h01 + h11| / 4.
  const Heightfield& hf = lbtest::testTerrain();
  ASSERT_EQ(hf.width, 129);
  const int w = 160, h = 90;
  Renderer r(gpu(), hf, {w, h, 2});
  r.setScheme(*findScheme("uniform"), {{"level", 64}});
  CameraPose pose = lbtest::poseAt({500, 900, -300}, {500, 0, 500});
  std::vector<float> err = r.renderErrorMap(pose, pose);

  // Bound per texel cell: world error <= |twist| / 4 anywhere in it, times the largest pixel length
  // of a vertical step that long at the cell's corners and centre (+5% for the variation in
  // between: cells are 7.8 units wide, 600+ units from the eye), plus the 1e-2 px of rasterization.
  CameraMatrices cam = cameraMatrices(pose, float(w) / float(h), hf.extent);
  glm::dmat4 viewProj = glm::dmat4(cam.proj) * glm::dmat4(cam.view);
  const double texel = hf.extent / double(hf.width - 1);
  double bound = 0, maxTwist = 0;
  for (int z = 0; z + 1 < hf.height; ++z)
    for (int x = 0; x + 1 < hf.width; ++x) {
      double err = std::abs(hf.at(x, z) - hf.at(x + 1, z) - hf.at(x, z + 1) + hf.at(x + 1, z + 1)) / 4.0;
      maxTwist = std::max(maxTwist, 4 * err);
      double scale = 0;
      for (glm::dvec2 c :
           {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1), glm::dvec2(0.5, 0.5)}) {
        glm::dvec3 p((x + c.x) * texel, hf.sample(float((x + c.x) * texel), float((z + c.y) * texel)),
                     (z + c.y) * texel);
        scale = std::max(
            scale, glm::length(toPixels(viewProj, p + glm::dvec3(0, err, 0), w, h) - toPixels(viewProj, p, w, h)));
      }
      bound = std::max(bound, 1.05 * scale);
    }
  bound += 1e-2;

  double maxErr = 0, sum = 0;
  int covered = 0;
  for (float e : err)
    if (e >= 0) maxErr = std::max(maxErr, double(e)), sum += e, ++covered;
  std::printf("[error validation] reference density: max %.4f px, mean %.5f px, bound %.4f px (twist %.3f)\n", maxErr,
              sum / covered, bound, maxTwist);
  EXPECT_GT(covered, w * h / 4);
  EXPECT_LE(maxErr, bound);
  EXPECT_LT(sum / covered, 0.02) << "reference density must be about exact on average";
  EXPECT_LT(bound, 0.5) << "the twist of this terrain stays well under a pixel from this camera";
}

TEST_F(ErrorValidation, ErrboundMeetsItsBoundOnTheGpu) {
  // errbound (which replaced the uniform-level oracle as the surplus reference) must keep its
  // promise on the trough, and not by a wide margin: the largest measured error is a sizeable
  // part of the bound (the bound is not vacuous).
  const Heightfield hf = trough();
  const int w = 320, h = 180, grid = 4;
  CameraPose pose = lbtest::poseAt({300, 400, -200}, {500, 100, 500});
  Renderer r(gpu(), hf, {w, h, grid});
  for (double bound : {0.5, 1.0, 2.0}) {
    r.setScheme(*findScheme("errbound"), {{"max_error_px", bound}});
    std::vector<float> err = r.renderErrorMap(pose, pose);
    double maxErr = double(*std::max_element(err.begin(), err.end()));
    std::printf("[error validation] errbound %.1f px: GPU max error %.3f px\n", bound, maxErr);
    EXPECT_LE(maxErr, 1.05 * bound);
    EXPECT_GT(maxErr, 0.1 * bound);
  }
}

namespace {

// Flat ground with a pillar half the extent tall between samples 40 and 48 of 129, scaled by s.
// uniform at level 1 on a 2 x 2 grid puts vertices on samples 0, 64 and 128 only, so it draws the
// ground flat through the pillar: the true point above a drawn pixel there is far above the camera.
Heightfield pillar(float s) {
  Heightfield hf;
  hf.width = hf.height = 129;
  hf.extent = kExtent * s;
  hf.h.assign(size_t(129) * 129, 0.0f);
  for (int z = 40; z <= 48; ++z)
    for (int x = 40; x <= 48; ++x) hf.h[size_t(z) * 129 + size_t(x)] = 0.5f * kExtent * s;
  hf.updateRange();
  return hf;
}

struct ErrorStats {
  int count = 0;
  double mean = 0, p95 = 0, max = 0;
  bool finite = true;
};

ErrorStats errorStats(const std::vector<float>& err) {
  ErrorStats st;
  std::vector<double> v;
  for (float e : err) {
    if (!std::isfinite(e)) st.finite = false;
    if (e >= 0) v.push_back(e);
  }
  std::sort(v.begin(), v.end());
  st.count = int(v.size());
  for (double e : v) st.mean += e / double(v.size());
  st.p95 = v.empty() ? 0 : v[size_t(0.95 * double(v.size() - 1))];
  st.max = v.empty() ? 0 : v.back();
  return st;
}

}  // namespace

TEST_F(ErrorValidation, TruePointsBehindTheCameraPlaneGiveABoundedScaleFreeError) {
  // A low camera looking down beside the pillar: raising a drawn point of its base by half the
  // extent takes it behind the camera. The error there is the segment cut at the near plane, capped
  // at the viewport diagonal (docs/results-format.md): finite, at most the diagonal, and the same
  // at x0.01 and x100 (before the rule, such pixels read up to 5.8e7 px and moved with the scale).
  const int w = 160, h = 90, grid = 2;
  const double diagonal = std::sqrt(double(w) * w + double(h) * h);
  std::vector<ErrorStats> stats;
  for (float s : {1.0f, 0.01f, 100.0f}) {
    Heightfield hf = pillar(s);
    Renderer r(gpu(), hf, {w, h, grid});
    r.setScheme(*findScheme("uniform"), {{"level", 1}});
    CameraPose pose = lbtest::poseAt(glm::vec3(300, 50, 300) * s, glm::vec3(345, 0, 345) * s);
    // The pillar's true top is behind the camera plane for the drawn base below it.
    CameraMatrices cam = cameraMatrices(pose, float(w) / float(h), hf.extent);
    glm::vec4 top = cam.proj * cam.view * glm::vec4(glm::vec3(344, 500, 344) * s, 1.0f);
    EXPECT_LT(top.z, 0.0f) << "the planted true point must lie behind the near plane";
    ErrorStats st = errorStats(r.renderErrorMap(pose, pose));
    std::printf("[error validation] pillar x%g: %d px, mean %.4f, p95 %.4f, max %.4f px (diagonal %.4f)\n", double(s),
                st.count, st.mean, st.p95, st.max, diagonal);
    EXPECT_TRUE(st.finite);
    EXPECT_GT(st.count, w * h / 2);
    EXPECT_LE(st.max, diagonal * (1 + 1e-6));
    stats.push_back(st);
  }
  // Pixels at the cap: the crossing really happens on screen, or the test proves nothing.
  EXPECT_NEAR(stats[0].max, diagonal, 1e-3 * diagonal);
  EXPECT_GT(stats[0].mean, 1.0);
  for (size_t i = 1; i < stats.size(); ++i) {
    EXPECT_EQ(stats[i].count, stats[0].count);
    EXPECT_NEAR(stats[i].mean, stats[0].mean, 0.01 * stats[0].mean);
    EXPECT_NEAR(stats[i].p95, stats[0].p95, 0.01 * stats[0].p95 + 1e-6);
    EXPECT_NEAR(stats[i].max, stats[0].max, 0.01 * stats[0].max);
  }
}
