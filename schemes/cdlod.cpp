// cdlod: F. Strugar, "Continuous Distance-Dependent Level of Detail for Rendering Heightmaps"
// (JGT 2009; paper and code 2010): a quadtree of square nodes, selected on the CPU by distance
// ranges that double per level, drawn as instances of one grid mesh whose vertices morph into the
// next coarser grid near the end of their range, so neighbours of different levels meet without
// cracks or skirts. Draw path: instanced grid (render/instanced.h); shader: shaders/cdlod.vert.
// Design note: docs/draw-paths.md. cdlod-sse (schemes/cdlod_sse.cpp) selects the same nodes
// (schemes/cdlod.h) by another rule.
//
// Nodes. A node at level l covers n * 2^l finest lattice cells a side (n = node_cells; lattice:
// render/instanced.h), drawn as its 4 quadrants, each one instance of an (n/2) x (n/2)-cell
// footprint scaled by 2^l. The root is the smallest power-of-two square holding the lattice;
// nodes and quadrants wholly past the last sample are never visited (the shader clamps vertices
// to the border, so a straddling quadrant is drawn clipped). Each node's box is its xz times the
// range of every sample its bilinear surface touches (a min-max pyramid:
// schemes/preprocess/min_max_pyramid.h; with node_cells auto, the levels finer than any node size
// drawn so far are made when a frame first draws that size, so a 1080p frame on a 65537^2 terrain
// never holds the 2.9 GB of 4-cell blocks).
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
#include "schemes/cdlod.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "error.h"
#include "number_text.h"
#include "shaders/cdlod_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
namespace cdlod {

using glm::dvec2;
using glm::dvec3;

bool isPowerOfTwo(double v) {
  int e = 0;
  return v > 0 && std::frexp(v, &e) == 0.5;
}

int log2Int(int v) {
  int l = 0;
  while ((1 << (l + 1)) <= v) ++l;
  return l;
}

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

NodeTree::NodeTree(const Heightfield& hf, const Settings& s, std::vector<int> candidates)
    : s_(s), candidates_(std::move(candidates)), hf_(&hf) {
  pyr_ = buildMinMaxPyramid(hf, s.cellsPerTexel, candidates_.front(), candidates_.back(),
                            latticeCell(hf.extent, hf.width, hf.height, s.cellsPerTexel),
                            finestLevelUsed(candidates_.back()));
  for (int n : candidates_) footprints_.push_back(footprint(n));
  flags_.resize(pyr_.nx.size());
  allocateFlags();
}

int NodeTree::finestLevelUsed(int n) const {
  // Nodes of n cells sit at pyramid levels from log2(n / base) up; their quadrants' boxes are the
  // blocks one level finer (level 0's quadrants take their node's).
  return std::max(0, log2Int(n / candidates_.front()) - 1);
}

void NodeTree::allocateFlags() const {
  for (int p = pyr_.built; p <= pyr_.top(); ++p)
    if (flags_[size_t(p)].empty()) flags_[size_t(p)].assign(size_t(pyr_.nx[size_t(p)]) * size_t(pyr_.nz[size_t(p)]), 0);
}

void NodeTree::select(const FrameUniforms& frame, Selection& out) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const NodeRef& r : touched_) flags_[size_t(r.p)][pyr_.index(r.p, r.i, r.j)] = 0;
  touched_.clear();
  out.instances.resize(footprints_.size());
  for (auto& v : out.instances) v.clear();
  out.counters.assign(s_.sse ? 2 : 1, 0.0);
  prepare(frame);
  selectNodes(frame, out);
}

Footprint NodeTree::footprint(int n) {
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

void NodeTree::prepare(const FrameUniforms& frame) const {
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
  if (finestLevelUsed(n_) < pyr_.built) {
    extendMinMaxPyramid(pyr_, *hf_, finestLevelUsed(n_));
    allocateFlags();
  }
  rootLevel_ = pyr_.top() - log2Int(n_ / pyr_.base);
  const double triSize = s_.sse ? 1.0 : s_.triSize;
  for (int l = 0; l <= rootLevel_ && l < kMaxLevels; ++l) {
    range_[l] = std::ldexp(c0 * K_ / triSize, l);
    const double prev = l == 0 ? 0.0 : range_[l - 1];
    start_[l] = range_[l] - s_.morph * (range_[l] - prev);
    end_[l] = range_[l] - 0.01 * (range_[l] - start_[l]);
  }
}

Box NodeTree::box(int p, int i, int j) const {
  const double s = pyr_.size(p);
  const glm::vec2 h = pyr_.bounds[size_t(p)][pyr_.index(p, i, j)];
  return rectBox(i * s, j * s, s, h.x, h.y);
}

Box NodeTree::rectBox(double x0, double z0, double s, double hmin, double hmax) const {
  const double x1 = std::min(x0 + s, pyr_.cellsX), z1 = std::min(z0 + s, pyr_.cellsZ);
  return {dvec3(origin_.x + x0 * pyr_.cell.x, hmin, origin_.y + z0 * pyr_.cell.y),
          dvec3(origin_.x + x1 * pyr_.cell.x, hmax, origin_.y + z1 * pyr_.cell.y)};
}

Box NodeTree::quadrantBox(int p, int ci, int cj) const {
  if (p > 0) return box(p - 1, ci, cj);
  const glm::vec2 h = pyr_.bounds[0][pyr_.index(0, ci / 2, cj / 2)];
  const double s = pyr_.size(-1);
  return rectBox(ci * s, cj * s, s, h.x, h.y);
}

bool NodeTree::childInside(int p, int ci, int cj) const {
  const double s = pyr_.size(p - 1);
  return ci * s < pyr_.cellsX && cj * s < pyr_.cellsZ;
}

void NodeTree::touch(int p, int i, int j, uint8_t f) const {
  uint8_t& v = flags(p, i, j);
  if (v == 0) touched_.push_back({p, i, j});
  v |= f;
}

void NodeTree::emit(Selection& out, int p, int ci, int cj, int level, const glm::vec4& kb, float kNode) const {
  const double s = pyr_.size(p - 1);
  const float code = float(level) + float(LB_CDLOD_SIDE_SHIFT) * float(n_ / 2);
  out.instances[fp_].push_back({glm::vec4(float(ci * s), float(cj * s), code, kNode), kb});
}

std::vector<ParamSpec> commonParams() {
  return {{"morph", LB_CDLOD_MORPH, 0.3, 0, 0.9, false,
           "fraction of each level's band (cdlod) or of the bound (cdlod-sse) over which vertices morph"},
          {"morph_on", LB_CDLOD_MORPH_ON, 1, 0, 1, true, "0 = no morphing (negative control: cracks and popping)"},
          {"node_cells", LB_CDLOD_NODE_CELLS, 0, 0, 128, true,
           "cells per node side at the finest level (power of two, 4..128); 0 = auto"},
          {"cells_per_texel", LB_CDLOD_CELLS_PER_TEXEL, 1, 0.25, 4, false,
           "finest grid cells per heightfield sample spacing (power of two)"}};
}

Settings settingsFrom(const ParamValues& v, bool sse) {
  Settings s;
  s.sse = sse;
  if (!sse)
    s.triSize = v.at("tri_size");
  else
    s.maxError = v.at("max_error_px");
  s.morph = v.at("morph");
  s.morphOn = v.at("morph_on") != 0;
  s.nodeCells = int(v.at("node_cells"));
  s.cellsPerTexel = v.at("cells_per_texel");
  return s;
}

void validateParams(const std::string& scheme, const ParamValues& v) {
  const double n = v.at("node_cells");
  if (n != 0 && !(isPowerOfTwo(n) && n >= 4))
    throw InputError("scheme '" + scheme + "': node_cells (" + numberText(n) +
                     ") must be 0 (auto) or a power of two from 4 to 128");
  const double q = v.at("cells_per_texel");
  if (!isPowerOfTwo(q))
    throw InputError("scheme '" + scheme + "': cells_per_texel (" + numberText(q) +
                     ") must be a power of two from 0.25 to 4");
}

}  // namespace cdlod

namespace {

using namespace cdlod;

constexpr int kAutoMinCells = 4, kAutoMaxCells = 64;

// One drawn quadrant: region (ci, cj) of the children grid of node level p.
struct Quad {
  int p, ci, cj, level;
  float hmin, hmax;
};

// Strugar's LODSelect and the seam check.
class DistanceLod : public NodeTree {
 public:
  DistanceLod(const Heightfield& hf, const Settings& s) : NodeTree(hf, s, candidates(s)) {}

 private:
  static std::vector<int> candidates(const Settings& s) {
    if (s.nodeCells > 0) return {s.nodeCells};
    std::vector<int> out;
    for (int n = kAutoMinCells; n <= kAutoMaxCells; n *= 2) out.push_back(n);
    return out;
  }

  void selectNodes(const FrameUniforms& /*frame*/, Selection& out) const override {
    quads_.clear();
    selectDistance(out);
  }

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

  mutable std::vector<Quad> quads_;
};

class Cdlod : public Scheme {
 public:
  const SchemeInfo& info() const override {
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
          .front = {2, 4, 8},
          .path = DrawPath::InstancedGrid,
          .vert = "cdlod",
          .counters = {{.frameKey = "cdlod_seam_risk", .caseKey = "cdlod_seam_risk_frames", .label = "seam possible"}},
      };
    }();
    return kInfo;
  }
  void validate(const ParamValues& v) const override { validateParams(info().name, v); }
  double targetAreaPx(const ParamValues& v) const override {
    const double t = v.at("tri_size");
    return t * t;
  }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return std::make_unique<DistanceLod>(hf, settingsFrom(v, false));
  }
};

}  // namespace

const Scheme& cdlodScheme() {
  static const Cdlod scheme;
  return scheme;
}

}  // namespace lb
