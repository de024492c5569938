// cdlod: F. Strugar, "Continuous Distance-Dependent Level of Detail for Rendering Heightmaps"
// (JGT 2009; paper and code 2010): a quadtree of square nodes, selected on the CPU by distance
// ranges that double per level, drawn as instances of one grid mesh whose vertices morph into the
// next coarser grid near the end of their range, so neighbours of different levels meet without
// cracks or skirts. Draw path: instanced grid (render/instanced.h); shader: shaders/cdlod.vert.
//
// cdlod-sse: the same nodes, footprint and shader with T. Ulrich's chunked-LOD rule ("Rendering
// Massive Terrains using Chunked Level of Detail Control", SIGGRAPH 2002 course): refine a node
// while its precomputed geometric error, projected at its nearest view depth, exceeds a pixel
// bound; then balance the tree 2:1 and morph by how far the parent's error is over the bound.
// Design note: docs/draw-paths.md.
//
// Nodes. A node at level l covers n * 2^l finest lattice cells a side (n = node_cells; lattice:
// render/instanced.h), drawn as its 4 quadrants, each one instance of an (n/2) x (n/2)-cell
// footprint scaled by 2^l. The root is the smallest power-of-two square holding the lattice;
// nodes and quadrants wholly past the last sample are never visited (the shader clamps vertices
// to the border, so a straddling quadrant is drawn clipped). Each node's box is its xz times the
// range of every sample its bilinear surface touches (a min-max pyramid built once).
//
// cdlod's constants, made scale-free. Strugar sets world ranges r_l = V (2^(l+1) - 1) / (2^L - 1)
// from a view range V; here r_l = 2^l c0 K / t (K = viewport height / (2 tan(fov/2)) from the LOD
// camera, c0 = the larger side of the finest cell, t = tri_size px): the same doubling, anchored
// so that a level-l cell is t px wide where its range ends and 2t px where the next finer range
// ends. Cells therefore span t..2t px in their band, triangles t^2/2..2 t^2 px^2, so the area a
// triangle histogram should centre on is t^2 (targetAreaPx), not the t^2/2 of a tessellated patch
// whose triangles are t px wide. Strugar morphs over "the last 15-30 % of every LOD range"; morph
// = mu is that fraction of the band: the morph starts at a_l = r_l - mu (r_l - r_(l-1)), with
// r_(-1) = 0 (level 0 also morphs into level 1 at its range's end), and ends 1 % of the morph
// short of r_l as in his code. His grid of 32 (leaf 8 x render-grid multiplier 4) becomes
// node_cells; his multiplier, i.e. cells finer than samples, becomes cells_per_texel (default 1:
// our truth surface is the bilinear heightfield, so finer cells only add triangles).
//
// Why cdlod has no cracks, and when it might. A quadrant is drawn at level l next to one at l+1
// only where the l-level child under the coarse quadrant lies wholly beyond r_l; the shared edge
// is on that child's box, so its fine vertices are at d >= r_l > morph end: fully morphed, they sit
// on the coarse vertices, computed from the same integers (bit-equal). Two more things must hold:
// the coarse side must not have started its own morph on that edge, and neighbours may differ by
// one level only. Both follow when a parent's box diagonal stays within (1 - mu) r_l, i.e.
// n <= (1 - mu) K c0 / (2 t |c|) (|c| the finest cell's diagonal; (1 - mu) K / (2 sqrt(2) t) for
// square cells), before heights enlarge the box. node_cells = 0 picks the largest power of two in
// [4, 64] meeting it on every frame: K is known only per frame (LOD resolution and fov), so the
// scheme keeps one footprint per candidate size and draws the frame's one. Every frame counts
// the shared edges where a crack is still possible (cdlod_seam_risk), from the same boxes.
//
// cdlod-sse. Node error delta_N: the largest vertical distance between N's triangulated grid (its
// level's cells, this file's diagonals, border clamp) and the bilinear heightfield, from the exact
// scan of schemes/preprocess/tess_deviation.h, at load. Screen error rho_N = delta_N K S / w_N with
// errbound's projection (schemes/errbound.cpp explains the bound): w_N the nearest view depth of
// the part of N's box inside each side plane of the LOD frustum, at least the near plane
// (extent 1e-4, so a box holding the eye gets the largest error a node of its delta can have, and a
// flat node none), S the off-axis factor. Refine while rho_N > max_error_px at l > 0, then split
// leaves until neighbours differ by one level at most. Morph: a node's k = clamp(((1 + mu) tau -
// rho_parent) / (mu tau), 0, 1), so a node whose parent only just needed refining looks like its
// parent; each quadrant edge takes 1 towards a coarser neighbour, 0 towards a finer one, the
// larger k towards an equal one: both sides of every edge agree, so no crack is possible.
// Level-0 leaves still over the bound are counted (cdlod_sse_unmet_nodes). Its main parameter is a
// Knob, not ErrorBoundPx: the surplus metric bisects errbound (the one ErrorBoundPx scheme the
// harness looks up), and while morphing the bound is (1 + mu) tau, not tau.
#include <algorithm>
#include <cmath>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "error.h"
#include "number_text.h"
#include "render/instanced.h"
#include "render/scheme.h"
#include "schemes/preprocess/tess_deviation.h"
#include "shaders/cdlod_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

using glm::dvec2;
using glm::dvec3;

constexpr int kAutoMinCells = 4, kAutoMaxCells = 64;
// cdlod-sse's node_cells = 0: Strugar's default grid of 32 (its seams need no range bound, so
// nothing ties n to the frame); quadrants of 16 x 16 cells (512 triangles) keep instances large
// enough for the GPU's instanced draws while the refinement stays fine-grained.
constexpr int kSseAutoCells = 32;
constexpr double kInf = std::numeric_limits<double>::infinity();

bool isPowerOfTwo(double v) {
  int e = 0;
  return v > 0 && std::frexp(v, &e) == 0.5;
}

int log2Int(int v) {
  int l = 0;
  while ((1 << (l + 1)) <= v) ++l;
  return l;
}

struct Box {
  dvec3 lo, hi;
};

double boxDistance2(const Box& b, const dvec3& p) {
  dvec3 d = glm::max(glm::max(b.lo - p, p - b.hi), dvec3(0.0));
  return glm::dot(d, d);
}

bool outsidePlanes(const Box& b, const glm::dvec4* planes) {
  for (int i = 0; i < 6; ++i) {
    const glm::dvec4& p = planes[i];
    dvec3 v(p.x >= 0 ? b.hi.x : b.lo.x, p.y >= 0 ? b.hi.y : b.lo.y, p.z >= 0 ? b.hi.z : b.lo.z);
    if (p.x * v.x + p.y * v.y + p.z * v.z + p.w < 0) return true;
  }
  return false;
}

// The lattice and its min-max pyramid. Pyramid level p holds blocks of base * 2^p lattice cells a
// side; a node of n cells at level l is block (p = l + log2(n / base)).
struct Pyramid {
  double cellsX = 0, cellsZ = 0;  // lattice extent in finest cells: (samples - 1) * cells_per_texel
  dvec2 cell{0};                  // finest cell in world units
  int base = 4;
  std::vector<int> nx, nz;
  std::vector<std::vector<glm::vec2>> bounds;  // (min, max) height per block
  int top() const { return int(nx.size()) - 1; }
  // base * 2^p as a product: exact for every level the pyramid has (p >= -1), and ldexp's library
  // call was a tenth of the per-frame selection.
  double size(int p) const { return p >= 0 ? double(base) * double(1u << p) : double(base) * 0.5; }
  size_t index(int p, int i, int j) const { return size_t(j) * size_t(nx[size_t(p)]) + size_t(i); }
};

Pyramid buildPyramid(const Heightfield& hf, double q, int base, int minTopCells) {
  Pyramid pyr;
  pyr.cellsX = double(hf.width - 1) * q;
  pyr.cellsZ = double(hf.height - 1) * q;
  pyr.cell = latticeCell(hf.extent, hf.width, hf.height, q);
  pyr.base = base;
  for (int p = 0;; ++p) {
    const double s = pyr.size(p);
    pyr.nx.push_back(int(std::ceil(pyr.cellsX / s)));
    pyr.nz.push_back(int(std::ceil(pyr.cellsZ / s)));
    if (pyr.nx.back() == 1 && pyr.nz.back() == 1 && s >= minTopCells) break;
  }
  pyr.bounds.resize(pyr.nx.size());
  // Level 0: every sample the bilinear surface over the block touches (lattice / q in texels; q
  // is a power of two, so the divisions are exact).
  const int nx0 = pyr.nx[0], nz0 = pyr.nz[0];
  pyr.bounds[0].assign(size_t(nx0) * size_t(nz0), glm::vec2(0));
  auto texelRange = [&](int i, double cells, int samples, int& t0, int& t1) {
    const double lo = double(i) * base, hi = std::min(double(i + 1) * base, cells);
    t0 = std::clamp(int(std::floor(lo / q)), 0, samples - 1);
    t1 = std::clamp(int(std::ceil(hi / q)), 0, samples - 1);
  };
  parallelRows(
      nz0,
      [&](int j0, int j1) {
        for (int j = j0; j < j1; ++j) {
          int z0, z1;
          texelRange(j, pyr.cellsZ, hf.height, z0, z1);
          for (int i = 0; i < nx0; ++i) {
            int x0, x1;
            texelRange(i, pyr.cellsX, hf.width, x0, x1);
            float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
            for (int z = z0; z <= z1; ++z) {
              const float* row = &hf.h[size_t(z) * size_t(hf.width)];
              for (int x = x0; x <= x1; ++x) {
                lo = std::min(lo, row[x]);
                hi = std::max(hi, row[x]);
              }
            }
            pyr.bounds[0][size_t(j) * size_t(nx0) + size_t(i)] = {lo, hi};
          }
        }
      },
      std::max(1, 4096 / std::max(1, nx0)));
  for (int p = 1; p <= pyr.top(); ++p) {
    pyr.bounds[size_t(p)].assign(size_t(pyr.nx[size_t(p)]) * size_t(pyr.nz[size_t(p)]),
                                 glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
    for (int j = 0; j < pyr.nz[size_t(p - 1)]; ++j)
      for (int i = 0; i < pyr.nx[size_t(p - 1)]; ++i) {
        glm::vec2 c = pyr.bounds[size_t(p - 1)][pyr.index(p - 1, i, j)];
        glm::vec2& b = pyr.bounds[size_t(p)][pyr.index(p, i / 2, j / 2)];
        b = {std::min(b.x, c.x), std::max(b.y, c.y)};
      }
  }
  return pyr;
}

// cdlod-sse's node errors: per pyramid level (= node level, base = n), the largest deviation of
// the node's cells of 2^l lattice cells, each split along its (0,0)-(1,1) diagonal as the
// footprint is, vertices clamped to the border as the shader clamps them.
struct NodeErrors {
  std::vector<std::vector<float>> dev;
};

NodeErrors computeNodeErrors(const Heightfield& hf, const Pyramid& pyr, double q) {
  NodeErrors out;
  out.dev.resize(pyr.nx.size());
  const int n = pyr.base;
  for (int p = 0; p <= pyr.top(); ++p) {
    const double s = std::ldexp(1.0, p);
    const int rows = int(std::ceil(pyr.cellsZ / s)), cols = int(std::ceil(pyr.cellsX / s));
    const int nodeCols = pyr.nx[size_t(p)];
    // Per cell row and node column, so that every level (the coarse ones have few node rows)
    // spreads over the threads.
    std::vector<float> rowMax(size_t(rows) * size_t(nodeCols), 0.0f);
    parallelRows(
        rows,
        [&](int r0, int r1) {
          for (int r = r0; r < r1; ++r) {
            const double z0 = r * s / q, z1 = std::min((r + 1) * s, pyr.cellsZ) / q;
            for (int c = 0; c < cols; ++c) {
              const double x0 = c * s / q, x1 = std::min((c + 1) * s, pyr.cellsX) / q;
              const dvec2 v00(x0, z0), v10(x1, z0), v11(x1, z1), v01(x0, z1);
              const double d = std::max(triangleDeviation(hf, v00, v10, v11), triangleDeviation(hf, v00, v11, v01));
              float& m = rowMax[size_t(r) * size_t(nodeCols) + size_t(c / n)];
              m = std::max(m, float(d));
            }
          }
        },
        std::max(1, 4096 / std::max(1, cols)));
    out.dev[size_t(p)].assign(size_t(nodeCols) * size_t(pyr.nz[size_t(p)]), 0.0f);
    for (int r = 0; r < rows; ++r)
      for (int i = 0; i < nodeCols; ++i) {
        float& d = out.dev[size_t(p)][pyr.index(p, i, r / n)];
        d = std::max(d, rowMax[size_t(r) * size_t(nodeCols) + size_t(i)]);
      }
  }
  return out;
}

// The scan costs seconds on large terrains and matched searches set the scheme once per candidate
// value: the last few tables are kept, keyed by the heights' content, node size and lattice.
std::shared_ptr<const NodeErrors> cachedNodeErrors(const Heightfield& hf, const Pyramid& pyr, double q) {
  struct Entry {
    int width, height, base;
    double q;
    uint64_t hash;
    std::shared_ptr<const NodeErrors> errors;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->base == pyr.base && it->q == q && it->hash == hash) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().errors;
    }
  cache.push_front(
      {hf.width, hf.height, pyr.base, q, hash, std::make_shared<const NodeErrors>(computeNodeErrors(hf, pyr, q))});
  if (cache.size() > 4) cache.pop_back();
  return cache.front().errors;
}

struct Settings {
  bool sse = false;
  double triSize = 3, morph = 0.3, maxError = 1, cellsPerTexel = 1;
  bool morphOn = true;
  int nodeCells = 0;
};

// Node state of one frame, per pyramid block.
enum : uint8_t {
  kQuadrants = 0x0f,  // cdlod: quadrants this node draws at its own level (bit = child x + 2 child z)
  kVisited = 0x10,    // in range (or the root) and not culled
  kLeaf = 0x20,       // cdlod-sse: drawn whole
  kRefined = 0x40,    // cdlod-sse: its unculled children are in the tree
};

struct NodeRef {
  int p, i, j;
};

// One drawn quadrant: region (ci, cj) of the children grid of node level p.
struct Quad {
  int p, ci, cj, level;
  float hmin, hmax;
};

class CdlodLod : public InstancedLod {
 public:
  CdlodLod(const Heightfield& hf, const Settings& s) : s_(s) {
    if (s.nodeCells > 0)
      candidates_ = {s.nodeCells};
    else if (s.sse)
      candidates_ = {kSseAutoCells};
    else
      for (int n = kAutoMinCells; n <= kAutoMaxCells; n *= 2) candidates_.push_back(n);
    pyr_ = buildPyramid(hf, s.cellsPerTexel, candidates_.front(), candidates_.back());
    for (int n : candidates_) footprints_.push_back(footprint(n));
    if (s.sse) errors_ = cachedNodeErrors(hf, pyr_, s.cellsPerTexel);
    flags_.resize(pyr_.nx.size());
    k_.resize(s.sse ? pyr_.nx.size() : 0);
    rho_.resize(s.sse ? pyr_.nx.size() : 0);
    for (size_t p = 0; p < pyr_.nx.size(); ++p) {
      flags_[p].assign(size_t(pyr_.nx[p]) * size_t(pyr_.nz[p]), 0);
      if (s.sse) {
        k_[p].assign(flags_[p].size(), 0.0f);
        rho_[p].assign(flags_[p].size(), 0.0f);
      }
    }
    leaves_.resize(pyr_.nx.size());
  }

  const std::vector<Footprint>& footprints() const override { return footprints_; }

  void select(const FrameUniforms& frame, Selection& out) const override {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const NodeRef& r : touched_) flags_[size_t(r.p)][pyr_.index(r.p, r.i, r.j)] = 0;
    touched_.clear();
    quads_.clear();
    out.instances.resize(footprints_.size());
    for (auto& v : out.instances) v.clear();
    out.counters.assign(s_.sse ? 2 : 1, 0.0);
    prepare(frame);
    if (s_.sse)
      selectSse(out);
    else
      selectDistance(out);
  }

 private:
  static Footprint footprint(int n) {
    Footprint f;
    const int side = n / 2;
    f.name = "quadrant" + std::to_string(side);
    for (int z = 0; z <= side; ++z)
      for (int x = 0; x <= side; ++x) f.vertices.emplace_back(float(x), float(z));
    auto at = [&](int x, int z) { return uint32_t(z * (side + 1) + x); };
    // Diagonal (0,0)-(1,1) in every cell: odd-odd vertices slide along it, so a fully morphed
    // 2 x 2 block is the coarse cell with the same diagonal (plus zero-area triangles).
    for (int z = 0; z < side; ++z)
      for (int x = 0; x < side; ++x)
        f.indices.insert(f.indices.end(),
                         {at(x, z), at(x + 1, z), at(x + 1, z + 1), at(x, z), at(x + 1, z + 1), at(x, z + 1)});
    return f;
  }

  void prepare(const FrameUniforms& frame) const {
    eye_ = dvec3(frame.lodEye);
    origin_ = dvec2(frame.origin.x, frame.origin.y);
    for (int i = 0; i < 6; ++i) planes_[i] = glm::dvec4(frame.frustum[i]);
    K_ = 0.5 * double(frame.viewport.y) * std::abs(double(frame.lodProj[1][1]));
    const double c0 = std::max(pyr_.cell.x, pyr_.cell.y);
    fp_ = 0;
    if (!s_.sse && candidates_.size() > 1) {
      const double limit = (1.0 - s_.morph) * K_ * c0 / (2.0 * s_.triSize * glm::length(pyr_.cell));
      for (size_t i = 0; i < candidates_.size(); ++i)
        if (candidates_[i] <= limit) fp_ = i;
    }
    n_ = candidates_[fp_];
    rootLevel_ = pyr_.top() - log2Int(n_ / pyr_.base);
    const double triSize = s_.sse ? 1.0 : s_.triSize;
    for (int l = 0; l <= rootLevel_ && l < kMaxLevels; ++l) {
      range_[l] = std::ldexp(c0 * K_ / triSize, l);
      const double prev = l == 0 ? 0.0 : range_[l - 1];
      start_[l] = range_[l] - s_.morph * (range_[l] - prev);
      end_[l] = range_[l] - 0.01 * (range_[l] - start_[l]);
    }
    if (s_.sse) prepareScreenError(frame);
  }

  // errbound's projection on the CPU (shaders/errbound.tesc): the LOD frustum's side planes and
  // the off-axis factor of a vertical error.
  void prepareScreenError(const FrameUniforms& frame) const {
    view_ = glm::dmat4(frame.lodView);
    const glm::dmat4 vp = glm::dmat4(frame.lodProj) * view_;
    auto row = [&](int r) { return glm::dvec4(vp[0][r], vp[1][r], vp[2][r], vp[3][r]); };
    sides_[0] = row(3) + row(0);
    sides_[1] = row(3) - row(0);
    sides_[2] = row(3) + row(1);
    sides_[3] = row(3) - row(1);
    near_ = double(frame.terrain.x) * 1e-4;
    const dvec3 u = dvec3(view_ * glm::dvec4(0, 1, 0, 0));
    const dvec2 halfScreen(1.0 / double(frame.lodProj[0][0]), 1.0 / std::abs(double(frame.lodProj[1][1])));
    offAxis_ = 0;
    for (int i = 0; i < 4; ++i) {
      dvec2 qs = halfScreen * dvec2((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0);
      offAxis_ = std::max(offAxis_, glm::length(dvec2(u) + qs * u.z));
    }
  }

  Box box(int p, int i, int j) const {
    const double s = pyr_.size(p);
    const glm::vec2 h = pyr_.bounds[size_t(p)][pyr_.index(p, i, j)];
    return rectBox(i * s, j * s, s, h.x, h.y);
  }
  Box rectBox(double x0, double z0, double s, double hmin, double hmax) const {
    const double x1 = std::min(x0 + s, pyr_.cellsX), z1 = std::min(z0 + s, pyr_.cellsZ);
    return {dvec3(origin_.x + x0 * pyr_.cell.x, hmin, origin_.y + z0 * pyr_.cell.y),
            dvec3(origin_.x + x1 * pyr_.cell.x, hmax, origin_.y + z1 * pyr_.cell.y)};
  }
  // The box of child region (ci, cj) of a node at pyramid level p; level 0 has no finer blocks,
  // so its quadrants take their node's heights.
  Box quadrantBox(int p, int ci, int cj) const {
    if (p > 0) return box(p - 1, ci, cj);
    const glm::vec2 h = pyr_.bounds[0][pyr_.index(0, ci / 2, cj / 2)];
    const double s = pyr_.size(-1);
    return rectBox(ci * s, cj * s, s, h.x, h.y);
  }
  bool childInside(int p, int ci, int cj) const {
    const double s = pyr_.size(p - 1);
    return ci * s < pyr_.cellsX && cj * s < pyr_.cellsZ;
  }
  bool inRange(const Box& b, int level) const { return boxDistance2(b, eye_) <= range_[level] * range_[level]; }
  uint8_t& flags(int p, int i, int j) const { return flags_[size_t(p)][pyr_.index(p, i, j)]; }
  void touch(int p, int i, int j, uint8_t f) const {
    uint8_t& v = flags(p, i, j);
    if (v == 0) touched_.push_back({p, i, j});
    v |= f;
  }

  void emit(Selection& out, int p, int ci, int cj, int level, const glm::vec4& kb, float kNode) const {
    const double s = pyr_.size(p - 1);
    const float code = float(level) + float(LB_CDLOD_SIDE_SHIFT) * float(n_ / 2);
    out.instances[fp_].push_back({glm::vec4(float(ci * s), float(cj * s), code, kNode), kb});
  }

  // ---- cdlod: Strugar's LODSelect.
  void selectDistance(Selection& out) const {
    visitDistance(out, pyr_.top(), 0, 0, rootLevel_);
    // The seam check costs about as much as the selection: measured frames only (Selection).
    out.counters[0] = out.countersWanted ? double(seamRisk()) : std::nan("");
  }

  void visitDistance(Selection& out, int p, int i, int j, int level) const {
    const Box b = box(p, i, j);
    if (outsidePlanes(b, planes_)) return;
    touch(p, i, j, kVisited);
    const bool whole = level == 0 || !inRange(b, level - 1);
    for (int c = 0; c < 4; ++c) {
      const int ci = 2 * i + (c & 1), cj = 2 * j + (c >> 1);
      if (!childInside(p, ci, cj)) continue;
      const Box cb = quadrantBox(p, ci, cj);
      if (!whole && inRange(cb, level - 1)) {
        visitDistance(out, p - 1, ci, cj, level - 1);
        continue;
      }
      if (outsidePlanes(cb, planes_)) continue;
      flags(p, i, j) |= uint8_t(1 << c);
      quads_.push_back({p, ci, cj, level, float(cb.lo.y), float(cb.hi.y)});
      if (s_.morphOn)
        emit(out, p, ci, cj, level, glm::vec4(float(start_[level]), float(end_[level]), 0, 0), -1.0f);
      else
        emit(out, p, ci, cj, level, glm::vec4(0.0f), 0.0f);
    }
  }

  // The drawn quadrant across the edge of region (ci + dx, cj + dz) (children grid of level p):
  // its node level, or -1 when none is coarser (same level, finer, culled or off the terrain).
  int coarserNeighbour(int p, int ri, int rj) const {
    if (ri < 0 || rj < 0 || !childInside(p, ri, rj)) return -1;
    for (int pp = p; pp <= pyr_.top(); ++pp) {
      const uint8_t f = flags(pp, ri >> 1, rj >> 1);
      if (f & kVisited) return pp == p ? -1 : ((f >> ((ri & 1) + 2 * (rj & 1))) & 1 ? pp : -1);
      ri >>= 1;
      rj >>= 1;
    }
    return -1;
  }

  // Shared edges where the two sides' vertices may differ: levels more than one apart, or the
  // fine side not fully morphed somewhere on the edge, or the coarse side already morphing there.
  long seamRisk() const {
    long risk = 0;
    const int dirs[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (const Quad& q : quads_)
      for (const auto& d : dirs) {
        const int pc = coarserNeighbour(q.p, q.ci + d[0], q.cj + d[1]);
        if (pc < 0) continue;
        const int coarse = q.level + (pc - q.p);
        if (coarse - q.level > 1 || !s_.morphOn) {
          ++risk;
          continue;
        }
        // The edge as a vertical rectangle over the heights both sides' boxes allow: its vertices
        // lie in both (the across box is the one the selection found out of range).
        const Box across = quadrantBox(q.p, q.ci + d[0], q.cj + d[1]);
        const double hmin = std::max(double(q.hmin), across.lo.y),
                     hmax = std::max(hmin, std::min(double(q.hmax), across.hi.y));
        const double s = pyr_.size(q.p - 1);
        double x0 = q.ci * s, z0 = q.cj * s, x1 = std::min(x0 + s, pyr_.cellsX), z1 = std::min(z0 + s, pyr_.cellsZ);
        if (d[0] < 0) x1 = x0;
        if (d[0] > 0) x0 = x1;
        if (d[1] < 0) z1 = z0;
        if (d[1] > 0) z0 = z1;
        const Box e{dvec3(origin_.x + x0 * pyr_.cell.x, hmin, origin_.y + z0 * pyr_.cell.y),
                    dvec3(origin_.x + x1 * pyr_.cell.x, hmax, origin_.y + z1 * pyr_.cell.y)};
        const double dmin = std::sqrt(boxDistance2(e, eye_));
        double dmax = 0;
        for (int c = 0; c < 8; ++c) {
          dvec3 v((c & 1) ? e.hi.x : e.lo.x, (c & 2) ? e.hi.y : e.lo.y, (c & 4) ? e.hi.z : e.lo.z);
          dmax = std::max(dmax, glm::length(v - eye_));
        }
        if (dmin < end_[q.level] || dmax > start_[coarse]) ++risk;
      }
    return risk;
  }

  // ---- cdlod-sse: refine by projected node error, balance 2:1, morph by the parent's error.
  double screenError(const Box& b, float dev) const {
    if (dev <= 0.0f) return 0.0;
    dvec3 c[8];
    double d[8];
    for (int k = 0; k < 8; ++k) {
      c[k] = dvec3((k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z);
      d[k] = -(view_ * glm::dvec4(c[k], 1.0)).z;
    }
    double w = near_;
    for (const glm::dvec4& plane : sides_) {
      double sd[8], m = kInf;
      for (int k = 0; k < 8; ++k) sd[k] = glm::dot(dvec3(plane), c[k]) + plane.w;
      for (int k = 0; k < 8; ++k) {
        if (sd[k] >= 0) m = std::min(m, d[k]);
        for (int bit = 1; bit < 8; bit <<= 1) {
          const int j = k | bit;
          if ((k & bit) == 0 && (sd[k] >= 0) != (sd[j] >= 0))
            m = std::min(m, d[k] + (d[j] - d[k]) * (sd[k] / (sd[k] - sd[j])));
        }
      }
      w = std::max(w, m);
    }
    return double(dev) * K_ * offAxis_ / w;
  }
  float morphFrom(double rhoParent) const {
    if (!s_.morphOn) return 0.0f;
    const double tau = s_.maxError;
    if (s_.morph <= 0) return rhoParent > tau ? 0.0f : 1.0f;
    return float(std::clamp(((1.0 + s_.morph) * tau - rhoParent) / (s_.morph * tau), 0.0, 1.0));
  }
  // Puts node (p, i, j) in the tree as a leaf unless culled; its morph follows its parent's error.
  void addLeaf(int p, int i, int j, double rhoParent) const {
    const Box b = box(p, i, j);
    if (outsidePlanes(b, planes_)) return;
    const size_t at = pyr_.index(p, i, j);
    rho_[size_t(p)][at] = float(screenError(b, errors_->dev[size_t(p)][at]));
    k_[size_t(p)][at] = morphFrom(rhoParent);
    touch(p, i, j, kVisited | kLeaf);
    leaves_[size_t(p)].push_back({p, i, j});
  }
  void split(int p, int i, int j) const {
    uint8_t& f = flags(p, i, j);
    f = uint8_t((f & ~kLeaf) | kRefined);
    const double rho = rho_[size_t(p)][pyr_.index(p, i, j)];
    for (int c = 0; c < 4; ++c) {
      const int ci = 2 * i + (c & 1), cj = 2 * j + (c >> 1);
      if (childInside(p, ci, cj)) addLeaf(p - 1, ci, cj, rho);
    }
  }

  void selectSse(Selection& out) const {
    for (auto& l : leaves_) l.clear();
    const int top = pyr_.top();
    addLeaf(top, 0, 0, kInf);
    // Refine top-down: leaves of level l are final once every coarser leaf has been looked at.
    for (int p = top; p > 0; --p)
      for (size_t k = 0; k < leaves_[size_t(p)].size(); ++k) {
        const NodeRef r = leaves_[size_t(p)][k];
        if (rho_[size_t(p)][pyr_.index(p, r.i, r.j)] > s_.maxError) split(p, r.i, r.j);
      }
    // Balance bottom-up: a leaf's same-size neighbour must lie in a node at most one level
    // coarser; splitting a coarser leaf adds leaves of coarser levels only, checked later.
    const int dirs[4][2] = {{-1, 0}, {0, -1}, {1, 0}, {0, 1}};  // west, south, east, north
    for (int p = 0; p < top; ++p)
      for (size_t k = 0; k < leaves_[size_t(p)].size(); ++k) {
        const NodeRef r = leaves_[size_t(p)][k];
        if (!(flags(p, r.i, r.j) & kLeaf)) continue;
        for (const auto& d : dirs) {
          const int ri = r.i + d[0], rj = r.j + d[1];
          if (ri < 0 || rj < 0 || ri >= pyr_.nx[size_t(p)] || rj >= pyr_.nz[size_t(p)]) continue;
          int pp = p + 1;
          while (pp <= top && !(flags(pp, ri >> (pp - p), rj >> (pp - p)) & (kLeaf | kRefined))) ++pp;
          // In the tree at p + 1 already, or under a refined node that culled it: nothing to do.
          if (pp > top || pp == p + 1 || (flags(pp, ri >> (pp - p), rj >> (pp - p)) & kRefined)) continue;
          // A leaf two or more levels coarser: split it down to p + 1 (stopping at a culled child).
          for (; pp > p + 1 && (flags(pp, ri >> (pp - p), rj >> (pp - p)) & kLeaf); --pp)
            split(pp, ri >> (pp - p), rj >> (pp - p));
        }
      }
    long unmet = 0, risk = 0;
    for (int p = 0; p <= top; ++p)
      for (const NodeRef& r : leaves_[size_t(p)]) {
        if (!(flags(p, r.i, r.j) & kLeaf)) continue;
        const size_t at = pyr_.index(p, r.i, r.j);
        const int level = p;
        if (level == 0 && rho_[0][at] > s_.maxError) ++unmet;
        const float kNode = k_[size_t(p)][at];
        float edge[4];
        for (int e = 0; e < 4; ++e) edge[e] = edgeMorph(p, r.i + dirs[e][0], r.j + dirs[e][1], kNode, risk);
        for (int c = 0; c < 4; ++c) {
          const int cx = c & 1, cz = c >> 1, ci = 2 * r.i + cx, cj = 2 * r.j + cz;
          if (!childInside(p, ci, cj)) continue;
          const Box qb = quadrantBox(p, ci, cj);
          if (outsidePlanes(qb, planes_)) continue;
          const glm::vec4 kb(cx == 0 ? edge[0] : kNode, cz == 0 ? edge[1] : kNode, cx == 1 ? edge[2] : kNode,
                             cz == 1 ? edge[3] : kNode);
          emit(out, p, ci, cj, level, kb, kNode);
        }
      }
    out.counters[0] = double(unmet);
    out.counters[1] = double(risk);
  }
  // Morph factor of a leaf's edge towards its same-size neighbour region (i, j) at level p.
  float edgeMorph(int p, int i, int j, float kNode, long& risk) const {
    if (i < 0 || j < 0 || i >= pyr_.nx[size_t(p)] || j >= pyr_.nz[size_t(p)]) return kNode;
    const uint8_t f = flags(p, i, j);
    if (f & kLeaf) return std::max(kNode, k_[size_t(p)][pyr_.index(p, i, j)]);
    if (f & kRefined) return 0.0f;
    for (int pp = p + 1; pp <= pyr_.top(); ++pp) {
      i >>= 1;
      j >>= 1;
      const uint8_t g = flags(pp, i, j);
      if (g & kRefined) return kNode;  // culled neighbour
      if (g & kLeaf) {
        if (pp > p + 1) ++risk;
        return s_.morphOn ? 1.0f : 0.0f;
      }
    }
    return kNode;
  }

  static constexpr int kMaxLevels = 32;
  Settings s_;
  std::vector<int> candidates_;
  Pyramid pyr_;
  std::vector<Footprint> footprints_;
  std::shared_ptr<const NodeErrors> errors_;
  // Per-frame state: select() is const for its callers and reuses these (no allocation once warm).
  mutable std::mutex mutex_;
  mutable std::vector<std::vector<uint8_t>> flags_;
  mutable std::vector<std::vector<float>> k_, rho_;
  mutable std::vector<std::vector<NodeRef>> leaves_;
  mutable std::vector<NodeRef> touched_;
  mutable std::vector<Quad> quads_;
  mutable dvec3 eye_{0};
  mutable dvec2 origin_{0};
  mutable glm::dvec4 planes_[6];
  mutable glm::dvec4 sides_[4];
  mutable glm::dmat4 view_{1};
  mutable double K_ = 0, near_ = 0, offAxis_ = 1;
  mutable double range_[kMaxLevels] = {}, start_[kMaxLevels] = {}, end_[kMaxLevels] = {};
  mutable size_t fp_ = 0;
  mutable int n_ = 0, rootLevel_ = 0;
};

class Cdlod : public Scheme {
 public:
  explicit Cdlod(bool sse) : sse_(sse) {}
  const SchemeInfo& info() const override { return sse_ ? sseInfo() : distanceInfo(); }
  void validate(const ParamValues& v) const override {
    const double n = v.at("node_cells");
    if (n != 0 && !(isPowerOfTwo(n) && n >= 4))
      throw InputError("scheme '" + info().name + "': node_cells (" + numberText(n) +
                       ") must be 0 (auto) or a power of two from 4 to 128");
    const double q = v.at("cells_per_texel");
    if (!isPowerOfTwo(q))
      throw InputError("scheme '" + info().name + "': cells_per_texel (" + numberText(q) +
                       ") must be a power of two from 0.25 to 4");
  }
  double targetAreaPx(const ParamValues& v) const override {
    if (sse_) return 0.0;
    const double t = v.at("tri_size");
    return t * t;
  }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    Settings s;
    s.sse = sse_;
    if (!sse_)
      s.triSize = v.at("tri_size");
    else
      s.maxError = v.at("max_error_px");
    s.morph = v.at("morph");
    s.morphOn = v.at("morph_on") != 0;
    s.nodeCells = int(v.at("node_cells"));
    s.cellsPerTexel = v.at("cells_per_texel");
    return std::make_unique<CdlodLod>(hf, s);
  }

 private:
  static std::vector<ParamSpec> commonParams() {
    return {{"morph", LB_CDLOD_MORPH, 0.3, 0, 0.9, false,
             "fraction of each level's band (cdlod) or of the bound (cdlod-sse) over which vertices morph"},
            {"morph_on", LB_CDLOD_MORPH_ON, 1, 0, 1, true, "0 = no morphing (negative control: cracks and popping)"},
            {"node_cells", LB_CDLOD_NODE_CELLS, 0, 0, 128, true,
             "cells per node side at the finest level (power of two, 4..128); 0 = auto"},
            {"cells_per_texel", LB_CDLOD_CELLS_PER_TEXEL, 1, 0.25, 4, false,
             "finest grid cells per heightfield sample spacing (power of two)"}};
  }
  static const SchemeInfo& distanceInfo() {
    static const SchemeInfo kInfo = [] {
      std::vector<ParamSpec> params = {{"tri_size", LB_CDLOD_TRI_SIZE, 3, 0.5, 64, false,
                                        "cell width in pixels where each level's range ends (cells span t..2t px)"}};
      for (ParamSpec& p : commonParams()) params.push_back(p);
      return SchemeInfo{
          .name = "cdlod",
          .description =
              "CPU quadtree by doubling distance ranges, instanced grid quadrants morphing into the next level",
          .seed = "Strugar 2010, Continuous Distance-Dependent Level of Detail (LODSelect, morph vertex shader)",
          .params = params,
          .mainParam = "tri_size",
          .mainParamRole = MainParamRole::TriangleWidthPx,
          .path = DrawPath::InstancedGrid,
          .vert = "cdlod",
          .counters = {{.frameKey = "cdlod_seam_risk", .caseKey = "cdlod_seam_risk_frames", .label = "seam possible"}},
      };
    }();
    return kInfo;
  }
  static const SchemeInfo& sseInfo() {
    static const SchemeInfo kInfo = [] {
      std::vector<ParamSpec> params = {{"max_error_px", LB_CDLOD_MAX_ERROR_PX, 1, 0.1, 64, false,
                                        "refine a node while its projected geometric error exceeds this (pixels)"}};
      for (ParamSpec& p : commonParams()) params.push_back(p);
      return SchemeInfo{
          .name = "cdlod-sse",
          .description = "CDLOD nodes refined by projected precomputed error (chunked LOD), 2:1 balanced, morphing",
          .seed =
              "Ulrich 2002, Rendering Massive Terrains using Chunked Level of Detail Control (rho = K delta / D) "
              "on Strugar 2010's nodes",
          .params = params,
          .mainParam = "max_error_px",
          .mainParamRole = MainParamRole::Knob,
          .path = DrawPath::InstancedGrid,
          .vert = "cdlod",
          .counters = {{.frameKey = "cdlod_sse_unmet_nodes",
                        .caseKey = "cdlod_sse_unmet_frames",
                        .label = "frames with unmet bound"},
                       {.frameKey = "cdlod_sse_seam_risk",
                        .caseKey = "cdlod_sse_seam_risk_frames",
                        .label = "seam possible"}},
      };
    }();
    return kInfo;
  }
  bool sse_;
};

}  // namespace

const Scheme& cdlodScheme() {
  static const Cdlod scheme(false);
  return scheme;
}

const Scheme& cdlodSseScheme() {
  static const Cdlod scheme(true);
  return scheme;
}

}  // namespace lb
