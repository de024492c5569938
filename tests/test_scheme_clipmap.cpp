// clipmap (schemes/clipmap.cpp), on the CPU: the footprints of every level tile its ring exactly
// once and the rings nest without gap or overlap; every vertex sits on its level's lattice; a twin
// of shaders/clipmap.vert's blend gives alpha = 1 exactly on every level's border and 0 inside; the
// twin's mesh is watertight with the degenerate strip and cracks without it (metrics/mesh_cracks.h);
// the finest level follows the eye's height; triangle counts follow the selection; culling keeps
// what the frustum sees; selections are scale-free.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

#include "metrics/mesh_cracks.h"
#include "render/instanced.h"
#include "render/scheme.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
const Scheme& clipmapScheme();
}

using namespace lb;

namespace {

// schemes/clipmap.cpp's footprint order; strips in three lengths (m - 1, m - 2, 2 coarse cells).
enum {
  kBlock,
  kFixupX,
  kFixupZ,
  kTrimX,
  kTrimZ,
  kCentre,
  kStripX,
  kStripZ = kStripX + 3,
  kFootprintCount = kStripZ + 3
};

bool isStrip(int f) {
  return f >= kStripX;
}
bool stripAlongX(int f) {
  return f >= kStripX && f < kStripZ;
}
int stripCoarseCells(int f, int m) {
  int k = (f - kStripX) % 3;
  return k == 0 ? m - 1 : k == 1 ? m - 2 : 2;
}

const Scheme& clipmap() {
  return clipmapScheme();
}

// Smooth relief with some high-frequency content, heights scaled by `scale` like the extent.
Heightfield terrain(int width, int height, float scale = 1.0f) {
  Heightfield hf;
  hf.width = width;
  hf.height = height;
  hf.extent = 1000.0f * scale;
  for (int z = 0; z < height; ++z)
    for (int x = 0; x < width; ++x)
      hf.h.push_back(scale * (60.0f * std::sin(0.05f * float(x)) * std::cos(0.07f * float(z)) +
                              5.0f * std::sin(0.9f * float(x + 2 * z)) + 80.0f));
  hf.updateRange();
  return hf;
}

std::unique_ptr<InstancedLod> lod(const Heightfield& hf, const ParamValues& given) {
  return clipmap().instancedLod(hf, resolveParams(clipmap().info(), given));
}

// A frame whose LOD eye is at lattice point (lx, lz), `height` world units above the ground under
// it, culling with a frustum that contains everything.
FrameUniforms frameAt(const Heightfield& hf, const ParamValues& given, double lx, double lz, double height,
                      glm::dvec2 origin = glm::dvec2(0.0)) {
  ParamValues v = resolveParams(clipmap().info(), given);
  glm::dvec2 c = latticeCell(hf.extent, hf.width, hf.height, v.at("cells_per_texel"));
  FrameUniforms f{};
  double x = lx * c.x, z = lz * c.y;
  double ground = hf.sample(float(x), float(z));
  f.lodEye = glm::vec4(float(origin.x + x), float(ground + height), float(origin.y + z), 1.0f);
  for (auto& p : f.frustum) p = glm::vec4(0, 0, 0, 1);
  f.terrain = glm::vec4(hf.extent, 16.0f, float(hf.width), float(hf.height));
  f.origin = glm::vec4(float(origin.x), float(origin.y), 0, 0);
  f.viewport = glm::vec4(640, 360, 1.0f / 640, 1.0f / 360);
  clipmap().update(f, v);
  return f;
}

Selection selectAt(const InstancedLod& l, const FrameUniforms& f) {
  Selection s;
  l.select(f, s);
  return s;
}

// Footprint extent in its level's cells.
glm::ivec2 footprintSize(const Footprint& f) {
  glm::vec2 hi(0.0f);
  for (glm::vec2 v : f.vertices) hi = glm::max(hi, v);
  return glm::ivec2(hi);
}

// Eye positions in lattice units: fractional, on snapping boundaries, on and beyond the border.
std::vector<glm::dvec2> eyes(double sx, double sz) {
  std::vector<glm::dvec2> out = {{0.5 * sx + 0.3, 0.5 * sz + 0.7},
                                 {0, 0},
                                 {sx, sz},
                                 {64, 32},
                                 {37.25, 81.9},
                                 {sx - 0.01, 3.5},
                                 {-50.5, 20},
                                 {sx + 300, -100},
                                 {-5 * sx, 0.5 * sz}};
  uint32_t state = 12345;
  auto next = [&]() {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (int i = 0; i < 12; ++i) out.push_back({(1.6 * next() - 0.3) * sx, (1.6 * next() - 0.3) * sz});
  return out;
}

// The level squares the file comment defines, from the eye alone: origin (finest lattice units) of
// level l, clamping the eye one terrain width beyond the border as select() does.
glm::dvec2 clampedEye(glm::dvec2 e, double sx, double sz) {
  double reach = std::max(sx, sz);
  return {std::clamp(e.x, -reach, sx + reach), std::clamp(e.y, -reach, sz + reach)};
}
struct Sq {
  long long x, y;
};
long long squareOrigin(double e, int l, int m) {
  long long g = 1LL << l;
  return (2 * (long long)std::floor(e / double(g) / 2) - (2 * m - 2)) * g;
}

// CPU twin of shaders/clipmap.vert (origin 0): the same float operations in the same order.
struct Twin {
  const Heightfield& hf;
  float q;
  glm::vec2 cell, last;
  Twin(const Heightfield& h, float cellsPerTexel)
      : hf(h),
        q(cellsPerTexel),
        cell(h.extent / ((float(h.width) - 1.0f) * q), h.extent / ((float(h.height) - 1.0f) * q)),
        last((float(h.width) - 1.0f) * q, (float(h.height) - 1.0f) * q) {}
  glm::vec2 world(glm::vec2 lattice) const { return glm::clamp(lattice, glm::vec2(0.0f), last) * cell; }
  float height(glm::vec2 lattice) const {
    glm::vec2 w = world(lattice);
    return hf.sample(w.x, w.y);
  }
  static glm::ivec2 levelCell(const InstanceRecord& r, glm::vec2 lattice) {
    return glm::ivec2(int(lattice.x) >> int(r.a.w), int(lattice.y) >> int(r.a.w));
  }
  static float alpha(const InstanceRecord& r, glm::ivec2 c) {
    float w = r.b.z;
    if (!(w > 0.0f)) return 0.0f;
    float tx = std::fabs(float(c.x) - r.b.x) - r.b.w, tz = std::fabs(float(c.y) - r.b.y) - r.b.w;
    float tm = std::max(tx, tz);
    return tm >= w ? 1.0f : std::clamp(tm / w, 0.0f, 1.0f);
  }
  glm::vec3 vertex(const InstanceRecord& r, glm::vec2 local) const {
    float g = r.a.z;
    glm::vec2 lattice(r.a.x + local.x * g, r.a.y + local.y * g);
    glm::ivec2 c = levelCell(r, lattice);
    glm::ivec2 odd(c.x & 1, c.y & 1);
    float h = height(lattice), hc = h;
    if (odd.x + odd.y > 0) {
      glm::vec2 step = glm::vec2(odd) * g;
      hc = 0.5f * (height(lattice - step) + height(lattice + step));
    }
    float a = alpha(r, c);
    float y = (1.0f - a) * h + a * hc;
    glm::vec2 w = world(lattice);
    return {w.x, y, w.y};
  }
};

std::vector<glm::vec3> twinTriangles(const Twin& twin, const InstancedLod& l, const Selection& s) {
  std::vector<glm::vec3> tris;
  for (size_t f = 0; f < s.instances.size(); ++f) {
    const Footprint& fp = l.footprints()[f];
    for (const InstanceRecord& r : s.instances[f])
      for (uint32_t i : fp.indices) tris.push_back(twin.vertex(r, fp.vertices[i]));
  }
  return tris;
}

TEST(SchemeClipmap, InfoDeclaresTheInstancedPath) {
  const SchemeInfo& info = clipmap().info();
  EXPECT_EQ(info.path, DrawPath::InstancedGrid);
  EXPECT_EQ(info.vert, "clipmap");
  EXPECT_EQ(info.mainParam, "block");
  ASSERT_EQ(info.counters.size(), 1u);
  Heightfield hf = terrain(65, 65);
  auto l = lod(hf, {{"block", 8}});
  Selection s = selectAt(*l, frameAt(hf, {{"block", 8}}, 10, 10, 1.0));
  EXPECT_EQ(s.counters.size(), info.counters.size());
  EXPECT_EQ(s.instances.size(), l->footprints().size());
}

// Integer vertices; grid footprints are rectangles cut into counter-clockwise (upward-facing)
// triangles that cover them once; strips are zero-area triangles along one line.
TEST(SchemeClipmap, FootprintsAreLatticeMeshes) {
  Heightfield hf = terrain(65, 65);
  for (int m : {4, 5, 8, 64}) {
    auto l = lod(hf, {{"block", m}});
    const auto& fps = l->footprints();
    ASSERT_EQ(fps.size(), size_t(kFootprintCount));
    glm::ivec2 expected[kFootprintCount] = {{m - 1, m - 1}, {m - 1, 2}, {2, m - 1}, {2 * m, 1}, {1, 2 * m - 1}, {2, 2}};
    for (int f = kStripX; f < kFootprintCount; ++f) {
      int cells = 2 * stripCoarseCells(f, m);
      expected[f] = stripAlongX(f) ? glm::ivec2(cells, 0) : glm::ivec2(0, cells);
    }
    for (int f = 0; f < kFootprintCount; ++f) {
      const Footprint& fp = fps[size_t(f)];
      SCOPED_TRACE(fp.name + " m=" + std::to_string(m));
      EXPECT_EQ(footprintSize(fp), expected[f]);
      for (glm::vec2 v : fp.vertices) {
        EXPECT_EQ(v.x, std::floor(v.x));
        EXPECT_EQ(v.y, std::floor(v.y));
      }
      ASSERT_EQ(fp.indices.size() % 3, 0u);
      double area = 0;
      for (size_t i = 0; i < fp.indices.size(); i += 3) {
        glm::vec2 a = fp.vertices[fp.indices[i]], b = fp.vertices[fp.indices[i + 1]],
                  c = fp.vertices[fp.indices[i + 2]];
        double cross = double(b.x - a.x) * double(c.y - a.y) - double(c.x - a.x) * double(b.y - a.y);
        if (isStrip(f)) {
          EXPECT_EQ(cross, 0.0);
          EXPECT_EQ(fp.indices[i], i / 3 * 2);
          EXPECT_EQ(fp.indices[i + 1], i / 3 * 2 + 1);
          EXPECT_EQ(fp.indices[i + 2], i / 3 * 2 + 2);
        } else {
          EXPECT_GT(cross, 0.0);
        }
        area += 0.5 * cross;
      }
      EXPECT_EQ(area, double(expected[f].x) * double(expected[f].y));
      if (isStrip(f)) {
        EXPECT_EQ(fp.indices.size() / 3, size_t(stripCoarseCells(f, m)));
      }
    }
  }
}

// Culling off: on the finest lattice, every cell of the terrain is covered exactly once, by the
// finest drawn level whose square (from the file comment's rule) contains it; every instance lies
// in its level's square and outside the next finer one; every vertex is a multiple of its level's
// spacing; strips run along the border of every level but the coarsest.
TEST(SchemeClipmap, LevelsTileTheTerrainOnceAndNest) {
  struct Case {
    int width, height, m, q;
  };
  for (Case c : {Case{129, 129, 4, 1}, Case{129, 65, 5, 1}, Case{97, 129, 8, 2}, Case{65, 65, 64, 1}}) {
    Heightfield hf = terrain(c.width, c.height);
    ParamValues given{{"block", c.m}, {"cells_per_texel", c.q}};
    auto l = lod(hf, given);
    const auto& fps = l->footprints();
    const long long sx = (long long)(c.width - 1) * c.q, sz = (long long)(c.height - 1) * c.q;
    const long long side = 4 * c.m - 2;
    for (glm::dvec2 eye : eyes(double(sx), double(sz))) {
      for (double height : {0.5, 400.0}) {
        SCOPED_TRACE(testing::Message() << c.width << "x" << c.height << " m=" << c.m << " q=" << c.q << " eye ("
                                        << eye.x << ", " << eye.y << ") height " << height);
        Selection s = selectAt(*l, frameAt(hf, given, eye.x, eye.y, height));
        const int finest = int(s.counters.at(0));
        int coarsest = finest;
        for (const auto& list : s.instances)
          for (const InstanceRecord& r : list) coarsest = std::max(coarsest, int(r.a.w));
        const glm::dvec2 e = clampedEye(eye, double(sx), double(sz));
        auto square = [&](int lv) { return Sq{squareOrigin(e.x, lv, c.m), squareOrigin(e.y, lv, c.m)}; };
        // The coarsest drawn level covers the terrain; the one below it does not (or is the finest).
        Sq top = square(coarsest);
        EXPECT_TRUE(top.x <= 0 && top.y <= 0 && top.x + side * (1LL << coarsest) >= sx &&
                    top.y + side * (1LL << coarsest) >= sz);
        if (coarsest > finest) {
          Sq below = square(coarsest - 1);
          long long span = side * (1LL << (coarsest - 1));
          EXPECT_FALSE(below.x <= 0 && below.y <= 0 && below.x + span >= sx && below.y + span >= sz);
        }
        std::vector<int> cover(size_t(sx * sz), 0), owner(size_t(sx * sz), -1);
        std::map<std::pair<int, int>, std::vector<int>> stripCells;  // (level, side) -> uses per fine cell
        std::map<int, std::vector<std::array<long long, 4>>> rects;  // kept instances per level
        for (int f = 0; f < kFootprintCount; ++f) {
          glm::ivec2 size = footprintSize(fps[size_t(f)]);
          for (const InstanceRecord& r : s.instances[size_t(f)]) {
            const int lv = int(r.a.w);
            const long long g = 1LL << lv;
            ASSERT_EQ(r.a.z, float(g));
            ASSERT_GE(lv, finest);
            ASSERT_LE(lv, coarsest);
            // Lattice: the origin is a multiple of g, so every vertex (origin + integer * g) is.
            const long long x0 = (long long)r.a.x, z0 = (long long)r.a.y;
            ASSERT_EQ(double(x0), double(r.a.x));
            ASSERT_EQ(double(z0), double(r.a.y));
            ASSERT_EQ(x0 % g, 0);
            ASSERT_EQ(z0 % g, 0);
            const long long x1 = x0 + size.x * g, z1 = z0 + size.y * g;
            const Sq sq = square(lv);
            ASSERT_TRUE(x0 >= sq.x && z0 >= sq.y && x1 <= sq.x + side * g && z1 <= sq.y + side * g);
            if (isStrip(f)) {
              // On one side of its level's square, starting on an even vertex of it.
              ASSERT_LT(lv, coarsest);
              ASSERT_GT(r.b.z, 0.0f);
              const bool alongX = stripAlongX(f);
              const long long along0 = alongX ? x0 - sq.x : z0 - sq.y, at = alongX ? z0 - sq.y : x0 - sq.x;
              ASSERT_TRUE(at == 0 || at == side * g);
              ASSERT_EQ(along0 % (2 * g), 0);
              const int sideIndex = (alongX ? 2 : 0) + (at != 0);
              std::vector<int>& used = stripCells[{lv, sideIndex}];
              used.resize(size_t(side), 0);
              for (long long k = along0 / g; k < along0 / g + 2 * stripCoarseCells(f, c.m); ++k) ++used[size_t(k)];
              continue;
            }
            rects[lv].push_back({x0, z0, x1, z1});
            ASSERT_TRUE(x0 < sx && x1 > 0 && z0 < sz && z1 > 0) << "an instance off the terrain was kept";
            if (lv > finest) {
              // Outside the finer level's square.
              const Sq fine = square(lv - 1);
              const long long fs = side * (g / 2);
              ASSERT_TRUE(x1 <= fine.x || x0 >= fine.x + fs || z1 <= fine.y || z0 >= fine.y + fs);
            }
            for (long long z = std::max(z0, 0LL); z < std::min(z1, sz); ++z)
              for (long long x = std::max(x0, 0LL); x < std::min(x1, sx); ++x) {
                ++cover[size_t(z * sx + x)];
                owner[size_t(z * sx + x)] = lv;
              }
          }
        }
        long long bad = 0, wrongOwner = 0;
        for (long long z = 0; z < sz; ++z)
          for (long long x = 0; x < sx; ++x) {
            bad += cover[size_t(z * sx + x)] != 1;
            int expect = finest;
            for (;; ++expect) {
              Sq sq = square(expect);
              long long span = side * (1LL << expect);
              if (x >= sq.x && x + 1 <= sq.x + span && z >= sq.y && z + 1 <= sq.y + span) break;
            }
            wrongOwner += owner[size_t(z * sx + x)] != expect;
          }
        EXPECT_EQ(bad, 0) << "terrain cells not covered exactly once";
        EXPECT_EQ(wrongOwner, 0) << "cells drawn by another level than the finest whose square holds them";
        // Strips: each fine cell of a level's border once, exactly where the coarser level drew the
        // coarse cell beyond it.
        long long stripWrong = 0;
        for (int lv = finest; lv < coarsest; ++lv) {
          const Sq sq = square(lv);
          const long long g = 1LL << lv, span = side * g;
          for (int sideIndex = 0; sideIndex < 4; ++sideIndex) {
            const bool alongX = sideIndex >= 2, high = sideIndex & 1;
            std::vector<int> used =
                stripCells.count({lv, sideIndex}) ? stripCells[{lv, sideIndex}] : std::vector<int>();
            used.resize(size_t(side), 0);
            for (long long k = 0; k < side / 2; ++k) {
              // The coarse cell beyond fine cells 2k, 2k + 1 of this side.
              long long a0 = (alongX ? sq.x : sq.y) + 2 * k * g, a1 = a0 + 2 * g;
              long long b0 = (alongX ? sq.y : sq.x) + (high ? span : -2 * g), b1 = b0 + 2 * g;
              long long cx0 = alongX ? a0 : b0, cx1 = alongX ? a1 : b1, cz0 = alongX ? b0 : a0, cz1 = alongX ? b1 : a1;
              bool drawn = false;
              for (const auto& q : rects[lv + 1])
                drawn = drawn || (q[0] <= cx0 && q[2] >= cx1 && q[1] <= cz0 && q[3] >= cz1);
              // Strips clamped onto the terrain border are left out; one reaching into the terrain is
              // kept whole.
              const long long across = alongX ? sq.y + (high ? span : 0) : sq.x + (high ? span : 0);
              const long long acrossEnd = alongX ? sz : sx, alongEnd = alongX ? sx : sz;
              drawn = drawn && across > 0 && across < acrossEnd;
              if (a1 <= 0 || a0 >= alongEnd) continue;
              stripWrong += used[size_t(2 * k)] != int(drawn) || used[size_t(2 * k + 1)] != int(drawn);
            }
          }
        }
        EXPECT_EQ(stripWrong, 0);
      }
    }
  }
}

// The twin of the vertex shader's blend: alpha = 1.0 exactly on every vertex of every level's
// border (all levels but the coarsest, whose w is 0), 0.0 exactly where the transition has not
// begun, in particular on the border of the hole the finer level fills; between 0 and 1 elsewhere.
TEST(SchemeClipmap, AlphaIsOneOnEveryBorderAndZeroInside) {
  Heightfield hf = terrain(257, 257);
  for (int m : {4, 5, 7, 16, 64}) {
    ParamValues given{{"block", m}};
    auto l = lod(hf, given);
    const int n = 4 * m - 1, w = n / 10, side = n - 1;
    for (glm::dvec2 eye : eyes(256, 256)) {
      SCOPED_TRACE(testing::Message() << "m=" << m << " eye (" << eye.x << ", " << eye.y << ")");
      Selection s = selectAt(*l, frameAt(hf, given, eye.x, eye.y, 0.5));
      std::map<int, InstanceRecord> perLevel;
      for (const auto& list : s.instances)
        for (const InstanceRecord& r : list) perLevel[int(r.a.w)] = r;
      ASSERT_FALSE(perLevel.empty());
      const int coarsest = perLevel.rbegin()->first;
      const glm::dvec2 e = clampedEye(eye, 256, 256);
      for (auto& [lv, r] : perLevel) {
        if (lv == coarsest) {
          EXPECT_EQ(r.b.z, 0.0f);
          continue;
        }
        ASSERT_EQ(r.b.z, float(w));
        ASSERT_EQ(r.b.w, float(side / 2 - w - 1));
        const long long ox = squareOrigin(e.x, lv, m) >> lv, oz = squareOrigin(e.y, lv, m) >> lv;
        long long onBorder = 0, notOne = 0, holeNotZero = 0, innerNotZero = 0, outOfRange = 0;
        for (int j = 0; j <= side; ++j)
          for (int i = 0; i <= side; ++i) {
            glm::ivec2 c(int(ox + i), int(oz + j));
            float a = Twin::alpha(r, c);
            outOfRange += !(a >= 0.0f && a <= 1.0f);
            if (i == 0 || j == 0 || i == side || j == side) {
              ++onBorder;
              notOne += a != 1.0f;
            }
            bool holeBorder = (i == m - 1 || i == 3 * m - 1) && j >= m - 1 && j <= 3 * m - 1;
            holeBorder = holeBorder || ((j == m - 1 || j == 3 * m - 1) && i >= m - 1 && i <= 3 * m - 1);
            holeNotZero += holeBorder && a != 0.0f;
            double dx = std::fabs(double(c.x) - double(r.b.x)), dz = std::fabs(double(c.y) - double(r.b.y));
            innerNotZero += std::max(dx, dz) <= double(side / 2 - w - 1) && a != 0.0f;
          }
        EXPECT_EQ(onBorder, 4LL * side);
        EXPECT_EQ(notOne, 0) << "level " << lv;
        EXPECT_EQ(holeNotZero, 0) << "level " << lv;
        EXPECT_EQ(innerNotZero, 0) << "level " << lv;
        EXPECT_EQ(outOfRange, 0) << "level " << lv;
        // The record's eye is the viewer in level units (not the snapped centre).
        EXPECT_NEAR(r.b.x, e.x / double(1LL << lv), 1e-3);
        EXPECT_NEAR(r.b.y, e.y / double(1LL << lv), 1e-3);
      }
    }
  }
}

// The twin's mesh (heights blended, vertices clamped to the border) through the analytic crack
// check: no crack with the strip, T-junction cracks without it; the strip's triangles are the only
// extra ones.
TEST(SchemeClipmap, StripClosesTheTJunctions) {
  struct Case {
    int width, height, m, q;
  };
  for (Case c : {Case{129, 129, 4, 1}, Case{129, 97, 5, 2}, Case{65, 65, 16, 1}}) {
    Heightfield hf = terrain(c.width, c.height);
    Twin twin(hf, float(c.q));
    const double sx = double(c.width - 1) * c.q, sz = double(c.height - 1) * c.q;
    MeshCrackBounds border{{0.0f, 0.0f}, {hf.extent, hf.extent}};
    long long cracksWithout = 0;
    for (glm::dvec2 eye : eyes(sx, sz)) {
      SCOPED_TRACE(testing::Message() << c.width << "x" << c.height << " m=" << c.m << " eye (" << eye.x << ", "
                                      << eye.y << ")");
      ParamValues with{{"block", c.m}, {"cells_per_texel", c.q}, {"strip", 1}};
      ParamValues without{{"block", c.m}, {"cells_per_texel", c.q}, {"strip", 0}};
      auto lw = lod(hf, with), lo = lod(hf, without);
      Selection sw = selectAt(*lw, frameAt(hf, with, eye.x, eye.y, 0.5));
      Selection so = selectAt(*lo, frameAt(hf, without, eye.x, eye.y, 0.5));
      size_t stripsWith = 0;
      for (int f = kStripX; f < kFootprintCount; ++f) {
        EXPECT_TRUE(so.instances[size_t(f)].empty());
        stripsWith += sw.instances[size_t(f)].size();
      }
      for (int f = 0; f < kStripX; ++f) ASSERT_EQ(sw.instances[size_t(f)].size(), so.instances[size_t(f)].size());
      MeshCrackResult rw = meshCracks(twinTriangles(twin, *lw, sw), border);
      MeshCrackResult ro = meshCracks(twinTriangles(twin, *lo, so), border);
      EXPECT_EQ(rw.cracks, 0);
      EXPECT_EQ(rw.unpairedEdges, 0);
      EXPECT_EQ(rw.invalidTriangles, 0);
      cracksWithout += ro.cracks;
      // Without a strip a T-junction remains wherever a finer level's border crosses the terrain.
      if (stripsWith > 0) {
        EXPECT_GT(ro.cracks, 0);
      }
    }
    EXPECT_GT(cracksWithout, 0);
  }
}

// Culling cuts the rings anywhere, yet the twin's mesh shows no crack: a strip piece goes with the
// coarse instance beside it, so open edges are only ever the unpaired sides of culled neighbours.
TEST(SchemeClipmap, CulledMeshesHaveNoCracks) {
  Heightfield hf = terrain(129, 129);
  Twin twin(hf, 1.0f);
  MeshCrackBounds border{{0.0f, 0.0f}, {hf.extent, hf.extent}};
  uint32_t state = 99;
  auto next = [&]() {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  long long unpaired = 0;
  for (int m : {4, 5, 8}) {
    ParamValues given{{"block", m}};
    auto l = lod(hf, given);
    for (glm::dvec2 eye : eyes(128, 128)) {
      for (int k = 0; k < 4; ++k) {
        // Two vertical planes through points near the eye, in random directions.
        FrameUniforms f = frameAt(hf, given, eye.x, eye.y, 0.5);
        for (int p = 0; p < 2; ++p) {
          double angle = 6.283185307179586 * next();
          glm::dvec2 n(std::cos(angle), std::sin(angle));
          glm::dvec2 at =
              (glm::clamp(eye, glm::dvec2(0.0), glm::dvec2(128.0)) + 40.0 * (glm::dvec2(next(), next()) - 0.5)) *
              double(hf.extent / 128.0);
          f.frustum[p] = glm::vec4(float(n.x), 0.0f, float(n.y), float(-glm::dot(n, at)));
        }
        Selection s = selectAt(*l, f);
        MeshCrackResult r = meshCracks(twinTriangles(twin, *l, s), border);
        EXPECT_EQ(r.cracks, 0) << "m=" << m << " eye (" << eye.x << ", " << eye.y << ") planes " << k;
        unpaired += r.unpairedEdges;
      }
    }
  }
  EXPECT_GT(unpaired, 0);  // the planes did cut through drawn rings
}

// Level l is drawn once (n - 1) g_l >= activate * h_eye; the finest active level grows with the
// eye's height, is 0 near the ground and never passes the level that covers the terrain.
TEST(SchemeClipmap, FinestLevelFollowsEyeHeight) {
  Heightfield hf = terrain(257, 257);
  for (int m : {4, 16, 64}) {
    ParamValues given{{"block", m}};
    auto l = lod(hf, given);
    const double cell = hf.extent / 256.0, side = 4 * m - 2;
    int previous = -1;
    for (double h : {0.0, 0.01, 1.0, 5.0, 20.0, 60.0, 150.0, 400.0, 1000.0, 3000.0, 1e5}) {
      Selection s = selectAt(*l, frameAt(hf, given, 100.3, 140.6, h));
      int finest = int(s.counters.at(0));
      int coarsest = 0;
      for (const auto& list : s.instances)
        for (const InstanceRecord& r : list) coarsest = std::max(coarsest, int(r.a.w));
      int expect = 0;
      while (expect < coarsest && side * double(1 << expect) * cell < 2.5 * h) ++expect;
      EXPECT_EQ(finest, expect) << "m=" << m << " height " << h;
      EXPECT_GE(finest, previous);
      previous = finest;
      // The finest level is drawn as a full square: its centre and all 16 blocks (those on the terrain).
      bool finestFull = false;
      for (const InstanceRecord& r : s.instances[kCentre]) finestFull = finestFull || int(r.a.w) == finest;
      EXPECT_TRUE(finestFull || coarsest == finest) << "m=" << m << " height " << h;
      if (h <= 1.0) {
        EXPECT_EQ(finest, 0);
      }
    }
    EXPECT_GT(previous, 0);
  }
  // activate = 0: every level from 0, whatever the height.
  auto all = lod(hf, {{"activate", 0}});
  EXPECT_EQ(selectAt(*all, frameAt(hf, {{"activate", 0}}, 128, 128, 1e4)).counters.at(0), 0.0);
}

// The triangles the GPU will clip are the selection's instances times its footprints' triangles:
// here also the closed form of a layout with nothing dropped (a terrain exactly the size of the
// covering level's square, eye at its centre): a full square, rings of 3 (2m - 1)^2 cells, four
// strips of 2m - 1 triangles for every level but the coarsest.
TEST(SchemeClipmap, TriangleCountIsTheFootprintSum) {
  for (int m : {4, 8}) {
    const int side = 4 * m - 2, levels = 4;
    const int samples = side * (1 << (levels - 1)) + 1;
    Heightfield hf = terrain(samples, samples);
    ParamValues given{{"block", m}};
    auto l = lod(hf, given);
    Selection s = selectAt(*l, frameAt(hf, given, 0.5 * (samples - 1), 0.5 * (samples - 1), 0.1));
    long long sum = 0;
    for (size_t f = 0; f < s.instances.size(); ++f)
      sum += (long long)(s.instances[f].size() * (l->footprints()[f].indices.size() / 3));
    long long closed = 2LL * side * side + (levels - 1) * (6LL * (2 * m - 1) * (2 * m - 1) + 4LL * (2 * m - 1));
    EXPECT_EQ(s.counters.at(0), 0.0);
    EXPECT_EQ(sum, closed) << "m=" << m;
    EXPECT_EQ(s.instances[kBlock].size(), size_t(16 + 12 * (levels - 1)));
    size_t strips = 0;
    for (int f = kStripX; f < kFootprintCount; ++f) strips += s.instances[size_t(f)].size();
    EXPECT_EQ(strips, size_t(12 * (levels - 1)));  // three pieces a side
    EXPECT_EQ(s.instances[kCentre].size(), 1u);
  }
}

// A frustum plane x >= X (world) keeps exactly the instances whose clamped box reaches X; a plane
// below the terrain's lowest point culls everything; selections are reused without leftovers.
TEST(SchemeClipmap, CullsByBoxAndReusesTheSelection) {
  Heightfield hf = terrain(129, 129);
  ParamValues given{{"block", 8}};
  auto l = lod(hf, given);
  FrameUniforms f = frameAt(hf, given, 60.2, 70.9, 2.0, {500.0, -250.0});
  Selection everything = selectAt(*l, f);
  const double cell = hf.extent / 128.0, cut = 500.0 + 90.0 * cell;
  f.frustum[0] = glm::vec4(1, 0, 0, float(-cut));
  Selection half;
  half.instances.assign(3, {InstanceRecord{}});  // leftovers select() must clear
  l->select(f, half);
  ASSERT_EQ(half.instances.size(), everything.instances.size());
  for (size_t k = 0; k < everything.instances.size(); ++k) {
    glm::ivec2 size = footprintSize(l->footprints()[k]);
    size_t expected = 0;
    if (isStrip(int(k))) continue;  // they follow their coarse instance
    for (const InstanceRecord& r : everything.instances[k]) {
      double x1 = std::min(double(r.a.x) + size.x * double(r.a.z), 128.0);
      expected += 500.0 + x1 * cell >= cut;
    }
    EXPECT_EQ(half.instances[k].size(), expected) << l->footprints()[k].name;
  }
  f.frustum[0] = glm::vec4(0, -1, 0, hf.minHeight - 1.0f);  // keep y <= min - 1: nothing
  Selection none = selectAt(*l, f);
  EXPECT_EQ(none.instanceCount(), 0u);
  EXPECT_EQ(none.counters, everything.counters);
}

// Culling boxes bound every height the vertex shader can produce: with a plane keeping y >= Y, an
// instance any of whose vertices (the twin's: blended, clamped) reaches Y is kept. White noise on a
// terrain small enough for one-sample height tiles (a blended vertex reads samples beyond its
// instance), and smooth relief on one whose tiles span 8 samples.
TEST(SchemeClipmap, CullingBoxesHoldTheBlendedHeights) {
  Heightfield noise = terrain(129, 129);
  uint32_t state = 7;
  for (float& h : noise.h) {
    state = state * 1664525u + 1013904223u;
    h = 15.0f + 130.0f * float(state >> 8) / float(1u << 24);
  }
  noise.updateRange();
  Heightfield smooth = terrain(1025, 1025);
  struct Case {
    const Heightfield* hf;
    int m, q;
  };
  for (Case c : {Case{&noise, 4, 1}, Case{&noise, 5, 2}, Case{&smooth, 8, 1}}) {
    const Heightfield& hf = *c.hf;
    ParamValues given{{"block", c.m}, {"cells_per_texel", c.q}};
    auto l = lod(hf, given);
    Twin twin(hf, float(c.q));
    const double s = double(hf.width - 1) * c.q;
    for (glm::dvec2 eye : eyes(s, s)) {
      SCOPED_TRACE(testing::Message() << hf.width << " m=" << c.m << " q=" << c.q << " eye (" << eye.x << ", " << eye.y
                                      << ")");
      FrameUniforms f = frameAt(hf, given, eye.x, eye.y, 1.0);
      Selection all = selectAt(*l, f);
      // Every instance's highest vertex as the plane's height: the instance must survive it.
      std::vector<std::vector<float>> tops(all.instances.size());
      std::vector<float> planes;
      for (size_t k = 0; k < all.instances.size(); ++k)
        for (const InstanceRecord& r : all.instances[k]) {
          float top = -INFINITY;
          for (glm::vec2 v : l->footprints()[k].vertices) top = std::max(top, twin.vertex(r, v).y);
          tops[k].push_back(top);
          planes.push_back(top);
        }
      std::sort(planes.begin(), planes.end());
      planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
      long long missing = 0;
      for (size_t i = 0; i < planes.size(); ++i) {
        f.frustum[0] = glm::vec4(0, 1, 0, -planes[i]);
        Selection kept = selectAt(*l, f);
        for (size_t k = 0; k < all.instances.size(); ++k) {
          size_t reaching =
              size_t(std::count_if(tops[k].begin(), tops[k].end(), [&](float t) { return t >= planes[i]; }));
          missing += kept.instances[k].size() < reaching;
        }
      }
      EXPECT_EQ(missing, 0);
    }
  }
}

// Extent and heights x 0.01 and x 100 (eye and origin with them): the same instances and counters;
// only the eye in the records may differ by float rounding of the scaled eye.
TEST(SchemeClipmap, SelectionIsScaleFree) {
  for (int m : {4, 64}) {
    std::vector<Selection> per;
    for (float scale : {1.0f, 0.01f, 100.0f}) {
      Heightfield hf = terrain(129, 97, scale);
      ParamValues given{{"block", m}, {"cells_per_texel", 2}};
      auto l = lod(hf, given);
      std::vector<Selection> frames;
      for (glm::dvec2 eye : {glm::dvec2(40.3, 77.7), glm::dvec2(250.6, 10.2), glm::dvec2(-30.7, 300.1)})
        for (double h : {0.3, 15.0, 120.0}) {
          FrameUniforms f = frameAt(hf, given, eye.x, eye.y, h * scale, glm::dvec2(1000.0 * scale, -700.0 * scale));
          frames.push_back(selectAt(*l, f));
        }
      if (per.empty()) {
        per = frames;
        continue;
      }
      for (size_t i = 0; i < frames.size(); ++i) {
        EXPECT_EQ(frames[i].counters, per[i].counters) << "scale " << scale << " frame " << i;
        for (size_t k = 0; k < frames[i].instances.size(); ++k) {
          ASSERT_EQ(frames[i].instances[k].size(), per[i].instances[k].size()) << "scale " << scale << " frame " << i;
          for (size_t j = 0; j < frames[i].instances[k].size(); ++j) {
            const InstanceRecord &a = frames[i].instances[k][j], &b = per[i].instances[k][j];
            EXPECT_EQ(a.a, b.a);
            EXPECT_EQ(a.b.z, b.b.z);
            EXPECT_EQ(a.b.w, b.b.w);
            EXPECT_NEAR(a.b.x, b.b.x, 1e-4f * std::max(1.0f, std::fabs(b.b.x)));
            EXPECT_NEAR(a.b.y, b.b.y, 1e-4f * std::max(1.0f, std::fabs(b.b.y)));
          }
        }
      }
    }
  }
}

}  // namespace
