// cdlod and cdlod-sse (schemes/cdlod.cpp), their CPU selection alone: on several poses and terrains
// the drawn quadrants tile the visible terrain once, neighbours differ by one level at most, the
// morphed vertices of every edge between two quadrants coincide from both sides (emulating
// shaders/cdlod.vert's lattice arithmetic), the seam counter sees a planted violation of the level
// gap, the selection does not change with the world's scale, and cdlod-sse keeps its error bound on
// every drawn node above level 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "camera/camera_matrices.h"
#include "crop_rows.h"
#include "render/instanced.h"
#include "render/renderer.h"
#include "render/scheme.h"
#include "schemes/preprocess/min_max_pyramid.h"
#include "schemes/preprocess/node_errors.h"
#include "schemes/preprocess/tess_deviation.h"
#include "shaders/cdlod_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "threads_env.h"

namespace lb {
const Scheme& cdlodScheme();
const Scheme& cdlodSseScheme();
}  // namespace lb

using namespace lb;

namespace {

Heightfield procedural(int size, double scale = 1.0, float heightScale = 120.0f) {
  TerrainSpec s;
  s.size = size;
  s.seed = 3;
  s.extent = float(1000.0 * scale);
  s.heightScale = float(heightScale * scale);
  return makeProcedural(s);
}

// A pose in units of the extent, eye and target heights above the ground under them.
struct Pose {
  std::string name;
  glm::dvec3 eye, target;  // x, z in extents; y in extents above the ground (eye) or absolute (target)
};

const std::vector<Pose>& poses() {
  static const std::vector<Pose> p = {
      {"high", {0.5, 0.8, -0.2}, {0.5, 0.0, 0.5}},      {"low", {0.3, 0.01, 0.3}, {0.7, 0.0, 0.7}},
      {"grazing", {0.1, 0.003, 0.5}, {0.9, 0.05, 0.5}}, {"down", {0.45, 0.3, 0.55}, {0.45, 0.0, 0.5501}},
      {"away", {-0.2, 0.05, 0.5}, {-1.0, 0.05, 0.5}},   {"outside", {1.3, 0.15, 1.2}, {0.5, 0.0, 0.5}},
  };
  return p;
}

// FrameUniforms as Renderer::fillUniforms builds them (cameraMatrices, frustumPlanes), in double
// where the pose is built so that scaled worlds see the same picture.
FrameUniforms frameFor(const Heightfield& hf, const Pose& pose, int w, int h, const Scheme& scheme,
                       const ParamValues& params) {
  const double e = hf.extent;
  auto ground = [&](double x, double z) {
    return double(hf.sample(float(std::clamp(x, 0.0, 1.0) * e), float(std::clamp(z, 0.0, 1.0) * e)));
  };
  glm::vec3 eye(float(pose.eye.x * e), float(ground(pose.eye.x, pose.eye.z) + pose.eye.y * e), float(pose.eye.z * e));
  glm::vec3 target(float(pose.target.x * e), float(pose.target.y * e + ground(pose.target.x, pose.target.z)),
                   float(pose.target.z * e));
  glm::vec3 dir = target - eye;
  glm::vec3 up = std::abs(glm::normalize(dir).y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAt(eye, target, up);
  glm::mat4 proj = glm::perspective(glm::radians(60.0f), float(w) / float(h), hf.extent * 1e-4f, hf.extent * 4.0f);
  proj[1][1] *= -1.0f;
  FrameUniforms u{};
  u.viewProj = proj * view;
  u.lodView = view;
  u.lodProj = proj;
  u.lodEye = glm::vec4(eye, 1.0f);
  frustumPlanes(u.viewProj, u.frustum);
  u.viewport = glm::vec4(float(w), float(h), 1.0f / float(w), 1.0f / float(h));
  u.terrain = glm::vec4(hf.extent, 32.0f, float(hf.width), float(hf.height));
  u.origin = glm::vec4(float(hf.originX), float(hf.originZ), 0, 0);
  scheme.update(u, params);
  return u;
}

struct Quadrant {
  double x0, z0, size;  // lattice cells
  int level, side;
  InstanceRecord rec;
};

std::vector<Quadrant> quadrants(const Selection& sel) {
  std::vector<Quadrant> out;
  for (const auto& list : sel.instances)
    for (const InstanceRecord& r : list) {
      const int side = int(std::floor(r.a.z / float(LB_CDLOD_SIDE_SHIFT)));
      const int level = int(r.a.z) - int(LB_CDLOD_SIDE_SHIFT) * side;
      out.push_back({r.a.x, r.a.y, std::ldexp(double(side), level), level, side, r});
    }
  return out;
}

bool boxOutside(const FrameUniforms& u, glm::dvec3 lo, glm::dvec3 hi) {
  for (const glm::vec4& p : u.frustum) {
    glm::dvec3 v(p.x >= 0 ? hi.x : lo.x, p.y >= 0 ? hi.y : lo.y, p.z >= 0 ? hi.z : lo.z);
    if (double(p.x) * v.x + double(p.y) * v.y + double(p.z) * v.z + double(p.w) < 0) return true;
  }
  return false;
}

// Height range of the samples in texel rectangle [x0, x1] x [z0, z1] (q = 1: lattice = texels).
glm::dvec2 heightRange(const Heightfield& hf, int x0, int z0, int x1, int z1) {
  double lo = 1e300, hi = -1e300;
  for (int z = std::max(z0, 0); z <= std::min(z1, hf.height - 1); ++z)
    for (int x = std::max(x0, 0); x <= std::min(x1, hf.width - 1); ++x) {
      lo = std::min(lo, double(hf.at(x, z)));
      hi = std::max(hi, double(hf.at(x, z)));
    }
  return {lo, hi};
}

// Per finest cell (cells_per_texel 1): the index of the quadrant covering it, -1 = none. Fails
// the test on an overlap.
struct Raster {
  int w = 0, h = 0;
  std::vector<int> owner;
  int at(int x, int z) const {
    return x < 0 || z < 0 || x >= w || z >= h ? -2 : owner[size_t(z) * size_t(w) + size_t(x)];
  }
};

Raster rasterize(const Heightfield& hf, const std::vector<Quadrant>& qs, const std::string& what) {
  Raster r{hf.width - 1, hf.height - 1, {}};
  r.owner.assign(size_t(r.w) * size_t(r.h), -1);
  int overlaps = 0;
  for (size_t k = 0; k < qs.size(); ++k) {
    const Quadrant& q = qs[k];
    EXPECT_LT(q.x0, r.w) << what;
    EXPECT_LT(q.z0, r.h) << what;
    for (int z = int(q.z0); z < std::min(int(q.z0 + q.size), r.h); ++z)
      for (int x = int(q.x0); x < std::min(int(q.x0 + q.size), r.w); ++x) {
        int& o = r.owner[size_t(z) * size_t(r.w) + size_t(x)];
        overlaps += o != -1;
        o = int(k);
      }
  }
  EXPECT_EQ(overlaps, 0) << what;
  return r;
}

// The drawn quadrants cover every cell whose box touches the frustum exactly once, each drawn
// quadrant's box (its xz, its node's heights) touches the frustum, and neighbours differ by one
// level at most. Returns the raster for further checks.
Raster checkTiling(const Heightfield& hf, const FrameUniforms& u, const std::vector<Quadrant>& qs,
                   const std::string& what) {
  Raster r = rasterize(hf, qs, what);
  const glm::dvec2 cell = latticeCell(hf.extent, hf.width, hf.height, 1.0);
  int uncovered = 0, offscreen = 0, gaps = 0;
  for (int z = 0; z < r.h; ++z)
    for (int x = 0; x < r.w; ++x) {
      if (r.at(x, z) >= 0) continue;
      glm::dvec2 hr = heightRange(hf, x, z, x + 1, z + 1);
      uncovered += !boxOutside(u, {x * cell.x, hr.x, z * cell.y}, {(x + 1) * cell.x, hr.y, (z + 1) * cell.y});
    }
  for (const Quadrant& q : qs) {
    // The node's heights: level-0 quadrants of the smallest node size are culled with them.
    const double ns = 2 * q.size, nx0 = std::floor(q.x0 / ns) * ns, nz0 = std::floor(q.z0 / ns) * ns;
    glm::dvec2 hr = heightRange(hf, int(nx0), int(nz0), int(nx0 + ns), int(nz0 + ns));
    const double x1 = std::min(q.x0 + q.size, double(r.w)), z1 = std::min(q.z0 + q.size, double(r.h));
    offscreen += boxOutside(u, {q.x0 * cell.x, hr.x, q.z0 * cell.y}, {x1 * cell.x, hr.y, z1 * cell.y});
  }
  for (int z = 0; z < r.h; ++z)
    for (int x = 0; x < r.w; ++x) {
      const int a = r.at(x, z);
      if (a < 0) continue;
      for (int b : {r.at(x + 1, z), r.at(x, z + 1)})
        if (b >= 0) gaps += std::abs(qs[size_t(a)].level - qs[size_t(b)].level) > 1;
    }
  EXPECT_EQ(uncovered, 0) << what << ": visible cells no quadrant covers";
  EXPECT_EQ(offscreen, 0) << what << ": quadrants drawn outside the frustum";
  EXPECT_EQ(gaps, 0) << what << ": neighbouring cells more than one level apart";
  return r;
}

// shaders/cdlod.vert on the CPU, in lattice units: the morphed position of footprint vertex g of
// quadrant q (the distance morph in double: the test poses keep edge vertices off the band ends).
glm::dvec2 morphed(const Heightfield& hf, const FrameUniforms& u, const Quadrant& q, glm::dvec2 g) {
  const double scale = std::ldexp(1.0, q.level);
  const glm::dvec2 last(hf.width - 1, hf.height - 1);
  const glm::dvec2 p = glm::dvec2(q.x0, q.z0) + g * scale;
  const glm::dvec2 odd(std::fmod(g.x, 2.0), std::fmod(g.y, 2.0));
  glm::dvec2 k;
  const InstanceRecord& r = q.rec;
  if (r.a.w < 0) {
    const glm::dvec2 cell = latticeCell(hf.extent, hf.width, hf.height, 1.0);
    const glm::dvec2 c = glm::min(p, last) * cell;
    const glm::dvec3 v(c.x, hf.sample(float(c.x), float(c.y)), c.y);
    const double d = glm::length(v - glm::dvec3(u.lodEye));
    const double kk = r.b.y > r.b.x ? std::clamp((d - r.b.x) / (r.b.y - r.b.x), 0.0, 1.0) : (d >= r.b.x ? 1.0 : 0.0);
    k = {kk, kk};
  } else {
    const double side = q.side;
    k.x = g.y == 0 ? r.b.y : (g.y == side ? r.b.w : r.a.w);
    k.y = g.x == 0 ? r.b.x : (g.x == side ? r.b.z : r.a.w);
  }
  return glm::min(p - odd * k * scale, last);
}

// Every edge between two drawn quadrants: the fine side's morphed vertices on it are the coarse
// side's, and the other way round (no T-junction, no gap). Returns the edges that fail.
int crackedEdges(const Heightfield& hf, const FrameUniforms& u, const std::vector<Quadrant>& qs, const Raster& r) {
  int bad = 0;
  // Morphed lattice points of quadrant k on the segment of its boundary at x or z = line.
  auto edgePoints = [&](const Quadrant& q, int axis, double line, double lo, double hi) {
    std::set<std::pair<double, double>> pts;
    for (int a = 0; a <= q.side; ++a)
      for (int b = 0; b <= q.side; b += q.side) {
        glm::dvec2 g = axis == 0 ? glm::dvec2(b, a) : glm::dvec2(a, b);
        glm::dvec2 p = glm::dvec2(q.x0, q.z0) + g * std::ldexp(1.0, q.level);
        if ((axis == 0 ? p.x : p.y) != line) continue;
        const double t = axis == 0 ? p.y : p.x;
        if (t < lo || t > hi) continue;
        glm::dvec2 m = morphed(hf, u, q, g);
        pts.insert({m.x, m.y});
      }
    return pts;
  };
  std::set<std::pair<int, int>> seen;
  for (size_t k = 0; k < qs.size(); ++k) {
    const Quadrant& q = qs[k];
    // East and north neighbours, every cell along the edge.
    for (int axis = 0; axis < 2; ++axis) {
      const double line = (axis == 0 ? q.x0 : q.z0) + q.size;
      if (line >= (axis == 0 ? r.w : r.h)) continue;
      for (int t = 0; t < int(q.size); ++t) {
        const int o = axis == 0 ? r.at(int(line), int(q.z0) + t) : r.at(int(q.x0) + t, int(line));
        if (o < 0 || !seen.insert({int(k), o}).second) continue;
        const Quadrant& n = qs[size_t(o)];
        const double lo = std::max(axis == 0 ? q.z0 : q.x0, axis == 0 ? n.z0 : n.x0);
        const double hi = std::min((axis == 0 ? q.z0 : q.x0) + q.size, (axis == 0 ? n.z0 : n.x0) + n.size);
        const double end = std::min(hi, double(axis == 0 ? r.h : r.w));
        auto a = edgePoints(q, axis, line, lo, end), b = edgePoints(n, axis, line, lo, end);
        // Points the morph moved along the edge past its shared part land on the other side's
        // corner points; compare inside the shared segment.
        auto inside = [&](const std::set<std::pair<double, double>>& s) {
          std::set<std::pair<double, double>> o2;
          for (auto& p : s)
            if ((axis == 0 ? p.second : p.first) >= lo && (axis == 0 ? p.second : p.first) <= end) o2.insert(p);
          return o2;
        };
        bad += inside(a) != inside(b);
      }
    }
  }
  return bad;
}

ParamValues params(const Scheme& s, const ParamValues& given = {}) {
  ParamValues v = resolveParams(s.info(), given);
  s.validate(v);
  return v;
}

struct Case {
  std::string name;
  Heightfield hf;
};

std::vector<Case> terrains() {
  Heightfield p257 = procedural(257);
  return {{"procedural257", p257},
          {"procedural513", procedural(513)},
          {"nonsquare257x129", lbtest::cropRows(p257, 129)},
          {"flat", procedural(129, 1.0, 0.0f)}};
}

TEST(SchemeCdlod, QuadrantsTileTheVisibleTerrainOnceWithoutSeams) {
  const Scheme& scheme = cdlodScheme();
  const ParamValues v = params(scheme);
  for (const Case& c : terrains()) {
    auto lod = scheme.instancedLod(c.hf, v);
    ASSERT_TRUE(lod);
    ASSERT_EQ(lod->footprints().size(), 5u);  // auto: 4, 8, 16, 32, 64 cells a node
    Selection sel;
    for (const Pose& pose : poses()) {
      const std::string what = c.name + "/" + pose.name;
      FrameUniforms u = frameFor(c.hf, pose, 320, 180, scheme, v);
      lod->select(u, sel);
      ASSERT_EQ(sel.instances.size(), lod->footprints().size());
      ASSERT_EQ(sel.counters.size(), scheme.info().counters.size());
      std::vector<Quadrant> qs = quadrants(sel);
      Raster r = checkTiling(c.hf, u, qs, what);
      EXPECT_EQ(sel.counters[0], 0) << what << ": seam_risk";
      EXPECT_EQ(crackedEdges(c.hf, u, qs, r), 0) << what;
      if (pose.name == "away")
        EXPECT_EQ(sel.instanceCount(), 0u) << what;
      else
        EXPECT_GT(sel.instanceCount(), 0u) << what;
      if (pose.name == "low" && c.name == "procedural513") {
        std::set<int> levels;
        for (const Quadrant& q : qs) levels.insert(q.level);
        EXPECT_GE(levels.size(), 4u) << what << ": several levels in one frame";
      }
    }
  }
}

// The footprint: (n/2)^2 cells with the (0,0)-(1,1) diagonal, counter-clockwise seen from above as
// the tessellated patches are; 320x180 at 60 degrees picks n = 8 ((1 - 0.3) 156 / (2 sqrt 2 3) = 12.9).
TEST(SchemeCdlod, AutoNodeSizeFollowsTheResolution) {
  const Scheme& scheme = cdlodScheme();
  Heightfield hf = procedural(257);
  auto lod = scheme.instancedLod(hf, params(scheme));
  const Footprint& f = lod->footprints()[1];
  EXPECT_EQ(f.vertices.size(), 25u);
  EXPECT_EQ(f.indices.size(), 4u * 4u * 6u);
  EXPECT_EQ(f.vertices[f.indices[0]], glm::vec2(0, 0));
  EXPECT_EQ(f.vertices[f.indices[1]], glm::vec2(1, 0));
  EXPECT_EQ(f.vertices[f.indices[2]], glm::vec2(1, 1));
  Selection sel;
  const std::map<int, size_t> expect = {{160, 0}, {320, 1}, {640, 2}, {1280, 3}, {1920, 4}};
  for (auto [w, footprint] : expect) {
    lod->select(frameFor(hf, poses()[1], w, w * 9 / 16, scheme, params(scheme)), sel);
    for (size_t i = 0; i < sel.instances.size(); ++i)
      EXPECT_EQ(sel.instances[i].empty(), i != footprint) << w << " px wide, footprint " << i;
  }
}

// Auto node size builds the min-max pyramid's fine levels only when a frame first draws small
// nodes. One tree asked for frames from the largest node size down to the smallest (each frame
// extending the pyramid from a coarser level) and back up selects what a fresh tree selects for
// the same frame, record for record.
TEST(SchemeCdlod, FineLevelsMadeOnDemandSelectAsAFreshTree) {
  const Scheme& scheme = cdlodScheme();
  const ParamValues v = params(scheme);
  for (const Case& c : terrains()) {
    auto lod = scheme.instancedLod(c.hf, v);
    Selection sel, fresh;
    for (int w : {1920, 640, 1920, 160, 320, 1280}) {
      const std::string what = c.name + ", " + std::to_string(w) + " px";
      const FrameUniforms u = frameFor(c.hf, poses()[1], w, w * 9 / 16, scheme, v);
      lod->select(u, sel);
      scheme.instancedLod(c.hf, v)->select(u, fresh);
      ASSERT_EQ(sel.instances.size(), fresh.instances.size()) << what;
      for (size_t i = 0; i < sel.instances.size(); ++i) {
        ASSERT_EQ(sel.instances[i].size(), fresh.instances[i].size()) << what << ", footprint " << i;
        for (size_t k = 0; k < sel.instances[i].size(); ++k) {
          EXPECT_EQ(sel.instances[i][k].a, fresh.instances[i][k].a) << what;
          EXPECT_EQ(sel.instances[i][k].b, fresh.instances[i][k].b) << what;
        }
      }
      EXPECT_GT(sel.instanceCount(), 0u) << what;
    }
  }
}

// A pyramid built from a coarse level and extended down is the one built at once, bit for bit,
// on lattices finer and coarser than the samples and blocks that do not divide the terrain.
TEST(SchemeCdlod, MinMaxPyramidExtendedDownIsTheSameBits) {
  const Heightfield hf = lbtest::cropRows(procedural(97), 61);
  for (double q : {0.5, 1.0, 2.0})
    for (int base : {4, 8})
      for (int first : {1, 2, 4, 50}) {
        const glm::dvec2 cell(hf.extent / (96 * q));
        const MinMaxPyramid whole = buildMinMaxPyramid(hf, q, base, 64, cell);
        MinMaxPyramid lazy = buildMinMaxPyramid(hf, q, base, 64, cell, first);
        const std::string what = "q " + std::to_string(q) + ", base " + std::to_string(base);
        ASSERT_EQ(lazy.built, std::min(first, whole.top())) << what;
        EXPECT_TRUE(lazy.bounds[0].empty()) << what;
        EXPECT_EQ(lazy.bounds[size_t(lazy.top())], whole.bounds[size_t(whole.top())]) << what;
        extendMinMaxPyramid(lazy, hf, lazy.built / 2);
        extendMinMaxPyramid(lazy, hf, 0);
        ASSERT_EQ(lazy.built, 0) << what;
        for (int p = 0; p <= whole.top(); ++p) {
          ASSERT_FALSE(whole.bounds[size_t(p)].empty());
          EXPECT_EQ(lazy.bounds[size_t(p)], whole.bounds[size_t(p)]) << what << ", level " << p;
        }
      }
}

TEST(SchemeCdlod, SeamRiskSeesAPlantedLevelGapViolation) {
  const Scheme& scheme = cdlodScheme();
  Heightfield hf = procedural(513);
  const ParamValues v = params(scheme, {{"node_cells", 64}, {"tri_size", 8}});
  auto lod = scheme.instancedLod(hf, v);
  Selection sel;
  lod->select(frameFor(hf, poses()[1], 160, 90, scheme, v), sel);
  EXPECT_GT(sel.counters[0], 0);
  // Morph off: every level change is a possible seam, and the emulated vertices do crack.
  const ParamValues off = params(scheme, {{"morph_on", 0}});
  auto lodOff = scheme.instancedLod(hf, off);
  FrameUniforms u = frameFor(hf, poses()[1], 320, 180, scheme, off);
  lodOff->select(u, sel);
  EXPECT_GT(sel.counters[0], 0);
  std::vector<Quadrant> qs = quadrants(sel);
  EXPECT_GT(crackedEdges(hf, u, qs, rasterize(hf, qs, "morph off")), 0);
}

// Same picture at 0.01, 1 and 100 times the world: the same quadrants (lattice units), morph
// distances in proportion, and the same explicit morph factors.
TEST(SchemeCdlod, SelectionIsScaleFree) {
  for (const Scheme* scheme : {&cdlodScheme(), &cdlodSseScheme()}) {
    const ParamValues v = params(*scheme);
    Heightfield ref = procedural(257);
    auto lodRef = scheme->instancedLod(ref, v);
    for (double scale : {0.01, 100.0}) {
      Heightfield hf = procedural(257, scale);
      auto lod = scheme->instancedLod(hf, v);
      for (const Pose& pose : poses()) {
        const std::string what = scheme->info().name + "/" + pose.name + " x" + std::to_string(scale);
        Selection a, b;
        lodRef->select(frameFor(ref, pose, 320, 180, *scheme, v), a);
        lod->select(frameFor(hf, pose, 320, 180, *scheme, v), b);
        EXPECT_EQ(a.counters, b.counters) << what;
        ASSERT_EQ(a.instances.size(), b.instances.size());
        for (size_t f = 0; f < a.instances.size(); ++f) {
          ASSERT_EQ(a.instances[f].size(), b.instances[f].size()) << what;
          for (size_t i = 0; i < a.instances[f].size(); ++i) {
            const InstanceRecord &ra = a.instances[f][i], &rb = b.instances[f][i];
            EXPECT_EQ(ra.a.x, rb.a.x) << what;
            EXPECT_EQ(ra.a.y, rb.a.y) << what;
            EXPECT_EQ(ra.a.z, rb.a.z) << what;
            const double s = ra.a.w < 0 ? scale : 1.0;  // distances, or factors in [0, 1]
            EXPECT_NEAR(ra.a.w, rb.a.w, 1e-5) << what;
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(ra.b[c] * s, rb.b[c], 1e-5 * std::abs(ra.b[c] * s) + 1e-5) << what;
          }
        }
      }
    }
  }
}

// errbound's projected error bound (shaders/errbound.tesc), recomputed here: nearest view depth of
// the box inside each side plane of the LOD frustum (at least the near plane), off-axis factor.
double screenError(const FrameUniforms& u, glm::dvec3 lo, glm::dvec3 hi, double dev) {
  if (dev <= 0) return 0;
  const glm::dmat4 view(u.lodView), vp = glm::dmat4(u.lodProj) * view;
  auto row = [&](int r) { return glm::dvec4(vp[0][r], vp[1][r], vp[2][r], vp[3][r]); };
  const glm::dvec4 planes[4] = {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1)};
  double w = double(u.terrain.x) * 1e-4;
  for (const glm::dvec4& pl : planes) {
    // Depth is linear: its minimum over box-and-halfspace is at a corner or an edge crossing.
    double m = 1e300;
    for (int k = 0; k < 8; ++k) {
      glm::dvec3 ck((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
      double sk = glm::dot(glm::dvec3(pl), ck) + pl.w, dk = -(view * glm::dvec4(ck, 1)).z;
      if (sk >= 0) m = std::min(m, dk);
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (k & bit) continue;
        const int j = k | bit;
        glm::dvec3 cj((j & 1) ? hi.x : lo.x, (j & 2) ? hi.y : lo.y, (j & 4) ? hi.z : lo.z);
        double sj = glm::dot(glm::dvec3(pl), cj) + pl.w, dj = -(view * glm::dvec4(cj, 1)).z;
        if ((sk >= 0) != (sj >= 0)) m = std::min(m, dk + (dj - dk) * sk / (sk - sj));
      }
    }
    w = std::max(w, m);
  }
  const glm::dvec3 up(view * glm::dvec4(0, 1, 0, 0));
  double s = 0;
  for (int i = 0; i < 4; ++i) {
    glm::dvec2 q(((i & 1) ? 1.0 : -1.0) / u.lodProj[0][0], ((i & 2) ? 1.0 : -1.0) / std::abs(u.lodProj[1][1]));
    s = std::max(s, glm::length(glm::dvec2(up) + q * up.z));
  }
  return dev * 0.5 * u.viewport.y * std::abs(u.lodProj[1][1]) * s / w;
}

// Node error recomputed from its definition: every cell of the node at its level's size, split
// along (0,0)-(1,1), clamped to the border (cells_per_texel 1).
double nodeDeviation(const Heightfield& hf, double x0, double z0, int n, int level) {
  const double s = std::ldexp(1.0, level), X = hf.width - 1, Z = hf.height - 1;
  double worst = 0;
  for (int j = 0; j < n && z0 + j * s < Z; ++j)
    for (int i = 0; i < n && x0 + i * s < X; ++i) {
      const double a = x0 + i * s, b = z0 + j * s, c = std::min(a + s, X), d = std::min(b + s, Z);
      worst = std::max(
          {worst, triangleDeviation(hf, {a, b}, {c, b}, {c, d}), triangleDeviation(hf, {a, b}, {c, d}, {a, d})});
    }
  return worst;
}

TEST(SchemeCdlodSse, KeepsItsBoundAboveLevelZeroBalancedAndCrackFree) {
  const Scheme& scheme = cdlodSseScheme();
  for (double tau : {1.0, 4.0}) {
    const ParamValues v = params(scheme, {{"max_error_px", tau}});
    for (const Case& c : terrains()) {
      auto lod = scheme.instancedLod(c.hf, v);
      ASSERT_EQ(lod->footprints().size(), 1u);
      Selection sel;
      std::map<std::tuple<double, double, int>, double> devs;
      for (const Pose& pose : poses()) {
        const std::string what = c.name + "/" + pose.name + " tau " + std::to_string(tau);
        FrameUniforms u = frameFor(c.hf, pose, 320, 180, scheme, v);
        lod->select(u, sel);
        ASSERT_EQ(sel.counters.size(), 2u);
        std::vector<Quadrant> qs = quadrants(sel);
        Raster r = checkTiling(c.hf, u, qs, what);
        EXPECT_EQ(sel.counters[1], 0) << what << ": seam_risk";
        EXPECT_EQ(crackedEdges(c.hf, u, qs, r), 0) << what;
        // Every drawn node above level 0 is within the bound; level-0 nodes over it are counted.
        const glm::dvec2 cell = latticeCell(c.hf.extent, c.hf.width, c.hf.height, 1.0);
        std::set<std::pair<double, double>> unmet;
        int over = 0;
        for (const Quadrant& q : qs) {
          const double ns = 2 * q.size, nx0 = std::floor(q.x0 / ns) * ns, nz0 = std::floor(q.z0 / ns) * ns;
          auto key = std::make_tuple(nx0, nz0, q.level);
          if (!devs.count(key)) devs[key] = nodeDeviation(c.hf, nx0, nz0, 2 * q.side, q.level);
          glm::dvec2 hr = heightRange(c.hf, int(nx0), int(nz0), int(nx0 + ns), int(nz0 + ns));
          const double x1 = std::min(nx0 + ns, double(r.w)), z1 = std::min(nz0 + ns, double(r.h));
          const double rho =
              screenError(u, {nx0 * cell.x, hr.x, nz0 * cell.y}, {x1 * cell.x, hr.y, z1 * cell.y}, devs[key]);
          if (q.level > 0)
            over += rho > tau * (1 + 1e-6);
          else if (rho > tau * (1 + 1e-6))
            unmet.insert({nx0, nz0});
        }
        EXPECT_EQ(over, 0) << what;
        EXPECT_EQ(sel.counters[0], double(unmet.size())) << what;
        if (c.name == "flat") {
          EXPECT_LE(sel.instanceCount(), 4u) << what << ": a flat terrain needs the root only";
        }
      }
    }
  }
}

TEST(SchemeCdlod, ParametersAreChecked) {
  for (const Scheme* s : {&cdlodScheme(), &cdlodSseScheme()}) {
    EXPECT_THROW(params(*s, {{"node_cells", 12}}), std::exception);
    EXPECT_THROW(params(*s, {{"node_cells", 2}}), std::exception);
    EXPECT_THROW(params(*s, {{"cells_per_texel", 3}}), std::exception);
    EXPECT_NO_THROW(params(*s, {{"node_cells", 128}, {"cells_per_texel", 0.25}}));
    EXPECT_EQ(s->info().path, DrawPath::InstancedGrid);
    EXPECT_EQ(s->info().vert, "cdlod");
  }
  EXPECT_EQ(cdlodScheme().targetAreaPx(params(cdlodScheme(), {{"tri_size", 4}})), 16.0);
  EXPECT_EQ(cdlodSseScheme().targetAreaPx(params(cdlodSseScheme())), 0.0);
}

// Cells per texel and fixed node sizes: the lattice changes, the tiling rules do not.
TEST(SchemeCdlod, OtherLatticesTileToo) {
  Heightfield hf = procedural(257);
  for (const Scheme* s : {&cdlodScheme(), &cdlodSseScheme()})
    for (double q : {0.25, 2.0})
      for (int n : {0, 16}) {
        const ParamValues v = params(*s, {{"cells_per_texel", q}, {"node_cells", n}});
        auto lod = s->instancedLod(hf, v);
        Selection sel;
        for (const Pose& pose : poses()) {
          FrameUniforms u = frameFor(hf, pose, 320, 180, *s, v);
          lod->select(u, sel);
          // Coverage in lattice cells: areas sum to the visible part at most once.
          const double X = 256 * q;
          std::vector<uint8_t> cover(size_t(X * X), 0);
          int overlaps = 0;
          for (const Quadrant& qd : quadrants(sel))
            for (int z = int(qd.z0); z < std::min(qd.z0 + qd.size, X); ++z)
              for (int x = int(qd.x0); x < std::min(qd.x0 + qd.size, X); ++x)
                overlaps += cover[size_t(z * X + x)]++ > 0;
          EXPECT_EQ(overlaps, 0) << s->info().name << " q " << q << " n " << n << " " << pose.name;
          if (n == 0 || s == &cdlodSseScheme()) {
            EXPECT_EQ(sel.counters.back(), 0) << s->info().name << " q " << q << " n " << n << " " << pose.name;
          }
        }
      }
}

// Seeded random poses (eye above or beside the terrain, any direction, any height): the tiling,
// level and crack rules of both schemes hold on all of them, and cdlod's seam counter stays 0.
TEST(SchemeCdlod, RandomPosesKeepTheRules) {
  Heightfield hf = procedural(257);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> xz(-0.3, 1.3), up(0.002, 0.5), dir(-1, 1);
  for (const Scheme* s : {&cdlodScheme(), &cdlodSseScheme()}) {
    const ParamValues v = params(*s);
    auto lod = s->instancedLod(hf, v);
    Selection sel;
    for (int k = 0; k < 24; ++k) {
      Pose pose{"random" + std::to_string(k), {xz(rng), up(rng), xz(rng)}, {}};
      pose.target = pose.eye + glm::dvec3(dir(rng), -0.5 * std::abs(dir(rng)), dir(rng));
      pose.target.y = 0;
      const std::string what = s->info().name + "/" + pose.name;
      FrameUniforms u = frameFor(hf, pose, 320, 180, *s, v);
      lod->select(u, sel);
      std::vector<Quadrant> qs = quadrants(sel);
      Raster r = checkTiling(hf, u, qs, what);
      EXPECT_EQ(sel.counters.back(), 0) << what << ": seam_risk";
      EXPECT_EQ(crackedEdges(hf, u, qs, r), 0) << what;
    }
  }
}

}  // namespace

namespace {

// Every node's error the plain way: the largest deviation of its cells' two triangles, cell by cell.
std::vector<std::vector<float>> nodeErrorsCellByCell(const Heightfield& hf, const MinMaxPyramid& pyr, double q) {
  std::vector<std::vector<float>> out;
  for (int p = 0; p <= pyr.top(); ++p) {
    const double s = std::ldexp(1.0, p);
    const int cols = int(std::ceil(pyr.cellsX / s)), rows = int(std::ceil(pyr.cellsZ / s));
    std::vector<float> want(size_t(pyr.nx[size_t(p)]) * size_t(pyr.nz[size_t(p)]), 0.0f);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double x0 = c * s / q, x1 = std::min((c + 1) * s, pyr.cellsX) / q;
        const double z0 = r * s / q, z1 = std::min((r + 1) * s, pyr.cellsZ) / q;
        const glm::dvec2 v00(x0, z0), v10(x1, z0), v11(x1, z1), v01(x0, z1);
        float& m = want[pyr.index(p, c / pyr.base, r / pyr.base)];
        m = std::max(m, float(std::max(triangleDeviation(hf, v00, v10, v11), triangleDeviation(hf, v00, v11, v01))));
      }
    out.push_back(std::move(want));
  }
  return out;
}

}  // namespace

// cdlod-sse's node errors read node sizes that are multiples of 16 cells from one table of
// 16-cell blocks (schemes/preprocess/node_errors.cpp): every node's error equals the largest
// deviation of its cells' two triangles, scanned here cell by cell, for each node size and
// lattice, whatever order the sizes are asked in (a larger size first leaves the smaller one's
// higher levels to be added).
TEST(SchemeCdlodSse, NodeErrorsEqualACellByCellScanForEveryNodeSize) {
  TerrainSpec spec;
  spec.size = 97;  // 96 cells: blocks of 16, 32 and 64 do not all divide the lattice
  spec.seed = 9;
  spec.extent = 500;
  spec.heightScale = 80;
  const Heightfield hf = makeProcedural(spec);
  for (double q : {1.0, 2.0})
    for (int base : {64, 16, 32, 8, 48}) {
      const MinMaxPyramid pyr = buildMinMaxPyramid(hf, q, base, 1, glm::dvec2(spec.extent / (96 * q)));
      const NodeErrors e = computeNodeErrors(hf, pyr, q);
      ASSERT_EQ(e.dev.size(), pyr.nx.size());
      const std::vector<std::vector<float>> want = nodeErrorsCellByCell(hf, pyr, q);
      for (int p = 0; p <= pyr.top(); ++p)
        EXPECT_EQ(e.dev[size_t(p)], want[size_t(p)]) << "q " << q << ", node size " << base << ", level " << p;
    }
}

// The node errors skip every cell whose bound (a sample scan against the corners' bilinear patch
// plus a quarter of the corners' twist) is below its block's largest exact deviation so far. The
// bound must hold, and its slack cover the rounding, on what breaks a loose one: heights far from
// zero (a plateau at 8,800 m), single-sample spikes and pits, a flat block (every bound equal,
// zero), cells that are not whole samples (cells_per_texel 2 and 0.5 at the levels where a cell is
// a fraction of a sample or not on one), and 1 to 7 threads (bands of 1 to 16 rows per block).
TEST(SchemeCdlodSse, PrunedNodeErrorsAreTheSameBitsOnSpikesOffsetsAndFlats) {
  TerrainSpec spec;
  spec.size = 129;
  spec.seed = 21;
  spec.extent = 800;
  spec.heightScale = 120;
  Heightfield hf = makeProcedural(spec);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> at(0, 128);
  for (float& h : hf.h) h += 8800.0f;
  for (int k = 0; k < 40; ++k) hf.h[size_t(at(rng)) * 129 + size_t(at(rng))] += (k % 2 ? 300.0f : -300.0f);
  for (int z = 0; z < 40; ++z)
    for (int x = 0; x < 40; ++x) hf.h[size_t(z) * 129 + size_t(x)] = 8810.0f;
  hf.updateRange();
  ThreadsEnv env(1);
  for (int threads : {1, 3, 7}) {
    env.set(threads);
    hf.h.back() += 1.0f;  // other heights, so that the tables' cache (keyed by their hash) is not read
    for (double q : {1.0, 2.0, 0.5}) {
      const int base = 16;
      const MinMaxPyramid pyr = buildMinMaxPyramid(hf, q, base, 1, glm::dvec2(spec.extent / (128 * q)));
      const NodeErrors e = computeNodeErrors(hf, pyr, q);
      const std::vector<std::vector<float>> want = nodeErrorsCellByCell(hf, pyr, q);
      ASSERT_EQ(e.dev.size(), want.size());
      for (size_t p = 0; p < want.size(); ++p)
        EXPECT_EQ(e.dev[p], want[p]) << threads << " threads, q " << q << ", level " << p;
      EXPECT_GT(*std::max_element(want[2].begin(), want[2].end()), 100.0f);  // the spikes are in the table
    }
  }
}

// The top levels of cdlod-sse's node errors scan each triangle's samples in bands of rows on the
// terrain threads: the same bits as one scan, for triangles inside, across and outside the terrain
// and degenerate ones, with 1 to 7 bands (LODBENCH_THREADS, as the load benchmark sets it).
TEST(SchemeCdlodSse, TriangleDeviationInRowBandsIsTheSameBits) {
  TerrainSpec spec;
  spec.size = 1025;
  spec.seed = 4;
  spec.extent = 1000;
  spec.heightScale = 150;
  spec.detailToSpacing = true;
  const Heightfield hf = makeProcedural(spec);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coord(-80.0, 1100.0);
  ThreadsEnv env(1);
  int compared = 0;
  for (int threads : {1, 3, 7}) {
    env.set(threads);
    for (int k = 0; k < 40; ++k) {
      glm::dvec2 a(coord(rng), coord(rng)), b(coord(rng), coord(rng)), c(coord(rng), coord(rng));
      if (k % 10 == 0) c = a + 0.5 * (b - a);  // degenerate: on the edge a-b
      const double one = triangleDeviation(hf, a, b, c), banded = triangleDeviation(hf, a, b, c, true);
      EXPECT_EQ(one, banded) << threads << " threads, triangle " << k;
      compared += one > 0;
    }
  }
  EXPECT_GT(compared, 60);  // most triangles cross the terrain: the comparison is not of zeros
}
