#include "metrics/oracle.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <glm/glm.hpp>

#include "render/patch_grid.h"
#include "render/renderer.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

constexpr int kMaxLevel = 64;

// One heightfield sample of a patch, with everything about it that does not depend on L.
struct Sample {
  double u, v;        // position in the patch, [0, 1]
  glm::dvec4 base;    // clip position of (x, 0, z); (x, y, z) is base + y * viewProj[1]
  glm::dvec2 truePx;  // pixel position of the true point
  bool trueVisible;   // true point inside the frustum
};

bool insideClip(const glm::dvec4& c) {
  return c.w > 0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w && c.z >= 0 && c.z <= c.w;
}

// Same test as shaders/common.glsl boxOutsideFrustum.
bool boxOutside(const glm::vec4 planes[6], glm::vec3 lo, glm::vec3 hi) {
  for (int i = 0; i < 6; ++i) {
    const glm::vec4& p = planes[i];
    glm::vec3 v(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
    if (glm::dot(glm::vec3(p), v) + p.w < 0) return true;
  }
  return false;
}

class PatchOracle {
 public:
  PatchOracle(const Heightfield& hf, int grid, const glm::dmat4& viewProj, int width, int height, double boundPx)
      : hf_(hf), grid_(grid), vp_(viewProj), half_(0.5 * width, 0.5 * height), bound2_(boundPx * boundPx) {
    heights_.resize(size_t(kMaxLevel + 1) * size_t(kMaxLevel + 1));
  }

  // Smallest level meeting the bound on patch (pi, pj); kMaxLevel + 1 when none does.
  int level(int pi, int pj) {
    collectSamples(pi, pj);
    if (samples_.empty()) return 1;
    worst_ = 0;
    for (int level = 1; level <= kMaxLevel; ++level)
      if (meetsBound(level)) return level;
    return kMaxLevel + 1;
  }

 private:
  glm::dvec2 toPixels(const glm::dvec4& c) const { return glm::dvec2(c.x, c.y) / c.w * half_; }

  // Texel corners inside the patch, borders included (exact integer arithmetic on texel indices).
  void collectSamples(int pi, int pj) {
    samples_.clear();
    const int nx = hf_.width - 1, nz = hf_.height - 1;
    const int x0 = (pi * nx + grid_ - 1) / grid_, x1 = ((pi + 1) * nx) / grid_;
    const int z0 = (pj * nz + grid_ - 1) / grid_, z1 = ((pj + 1) * nz) / grid_;
    const double extent = double(hf_.extent);
    for (int z = z0; z <= z1; ++z)
      for (int x = x0; x <= x1; ++x) {
        double wx = nx > 0 ? extent * x / nx : 0, wz = nz > 0 ? extent * z / nz : 0;
        Sample s;
        s.u = nx > 0 ? double(x) * grid_ / nx - pi : 0;
        s.v = nz > 0 ? double(z) * grid_ / nz - pj : 0;
        s.base = vp_ * glm::dvec4(wx, 0, wz, 1);
        glm::dvec4 c = s.base + double(hf_.at(x, z)) * vp_[1];
        s.trueVisible = insideClip(c);
        s.truePx = c.w > 0 ? toPixels(c) : glm::dvec2(0);
        if (c.w > 0) samples_.push_back(s);  // behind the camera: never seen
      }
    cx0_ = hf_.extent * float(pi) / float(grid_);
    cx1_ = hf_.extent * float(pi + 1) / float(grid_);
    cz0_ = hf_.extent * float(pj) / float(grid_);
    cz1_ = hf_.extent * float(pj + 1) / float(grid_);
  }

  // True height at tessellation vertex (k, l) of level `level_`, xz computed as terrain_quad.tese does.
  float vertexHeight(int k, int l) {
    float& h = heights_[size_t(l) * size_t(level_ + 1) + size_t(k)];
    if (std::isnan(h)) {
      float u = float(k) / float(level_), v = float(l) / float(level_);
      h = hf_.sample(cx0_ * (1.0f - u) + cx1_ * u, cz0_ * (1.0f - v) + cz1_ * v);
    }
    return h;
  }

  // Bilinear interpolation of the level-L vertex heights at patch position (u, v).
  double surfaceHeight(double u, double v) {
    double fu = u * level_, fv = v * level_;
    int k = std::clamp(int(fu), 0, level_ - 1), l = std::clamp(int(fv), 0, level_ - 1);
    fu -= k;
    fv -= l;
    double h0 = vertexHeight(k, l) * (1 - fu) + vertexHeight(k + 1, l) * fu;
    double h1 = vertexHeight(k, l + 1) * (1 - fu) + vertexHeight(k + 1, l + 1) * fu;
    return h0 * (1 - fv) + h1 * fv;
  }

  bool sampleFails(const Sample& s) {
    glm::dvec4 c = s.base + surfaceHeight(s.u, s.v) * vp_[1];
    if (!s.trueVisible && !insideClip(c)) return false;
    if (c.w <= 0) return true;  // the coarse surface passes behind the eye: unbounded error
    glm::dvec2 d = toPixels(c) - s.truePx;
    return glm::dot(d, d) > bound2_;
  }

  bool meetsBound(int level) {
    level_ = level;
    std::fill_n(heights_.begin(), size_t(level + 1) * size_t(level + 1), NAN);
    // The sample that failed the previous level most likely fails this one too: try it first.
    if (sampleFails(samples_[worst_])) return false;
    for (size_t i = 0; i < samples_.size(); ++i)
      if (i != worst_ && sampleFails(samples_[i])) {
        worst_ = i;
        return false;
      }
    return true;
  }

  const Heightfield& hf_;
  int grid_;
  glm::dmat4 vp_;
  glm::dvec2 half_;
  double bound2_;
  std::vector<Sample> samples_;
  std::vector<float> heights_;  // lazily filled vertex heights of the current level
  int level_ = 1;
  size_t worst_ = 0;
  float cx0_ = 0, cx1_ = 0, cz0_ = 0, cz1_ = 0;
};

}  // namespace

OracleResult surplusOracle(const Heightfield& hf, int grid, const CameraMatrices& cam, int width, int height,
                           double boundPx) {
  assert(grid >= 1 && width >= 1 && height >= 1 && boundPx >= 0 && hf.width >= 1 && hf.height >= 1);
  const glm::mat4 viewProj = cam.proj * cam.view;
  glm::vec4 planes[6];
  frustumPlanes(viewProj, planes);
  const std::vector<glm::vec2> bounds = patchHeightBounds(hf, grid, Topology::Quad4);
  PatchOracle oracle(hf, grid, glm::dmat4(viewProj), width, height, boundPx);

  OracleResult r;
  r.levels.assign(size_t(grid) * size_t(grid), 0);
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const size_t p = size_t(j) * size_t(grid) + size_t(i);
      // Corner xz as gridVertices() computes them, height range as the renderer uploads it.
      glm::vec2 lo(hf.extent * float(i) / float(grid), hf.extent * float(j) / float(grid));
      glm::vec2 hi(hf.extent * float(i + 1) / float(grid), hf.extent * float(j + 1) / float(grid));
      if (boxOutside(planes, glm::vec3(lo.x, bounds[p].x, lo.y), glm::vec3(hi.x, bounds[p].y, hi.y))) continue;
      int level = oracle.level(i, j);
      if (level > kMaxLevel) {
        level = kMaxLevel;
        ++r.saturated;
      }
      r.levels[p] = level;
      r.triangles += 2 * uint64_t(level) * uint64_t(level);
      ++r.patches;
    }
  return r;
}

}  // namespace lb
