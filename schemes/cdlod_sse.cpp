// cdlod-sse: the nodes, footprint and shader of cdlod (schemes/cdlod.cpp, schemes/cdlod.h) with
// T. Ulrich's chunked-LOD rule ("Rendering Massive Terrains using Chunked Level of Detail Control",
// SIGGRAPH 2002 course): refine a node while its precomputed geometric error, projected at its
// nearest view depth, exceeds a pixel bound; then balance the tree 2:1 and morph by how far the
// parent's error is over the bound. Design note: docs/draw-paths.md.
//
// Node error delta_N: the largest vertical distance between N's triangulated grid (its level's
// cells, the footprint's diagonals, border clamp) and the bilinear heightfield, from the exact scan
// of schemes/preprocess/tess_deviation.h, at load (schemes/preprocess/node_errors.h). Screen error rho_N = delta_N K S
// / w_N with errbound's projection (schemes/errbound.cpp explains the bound): w_N the nearest view depth of the part of
// N's box inside each side plane of the LOD frustum, at least the near plane (extent 1e-4, so a box holding the eye
// gets the largest error a node of its delta can have, and a flat node none), S the off-axis factor. Refine while rho_N
// > max_error_px at l > 0, then split leaves until neighbours differ by one level at most. Morph: a node's k =
// clamp(((1 + mu) tau - rho_parent) / (mu tau), 0, 1), so a node whose parent only just needed refining looks like its
// parent; each quadrant edge takes 1 towards a coarser neighbour, 0 towards a finer one, the
// larger k towards an equal one: both sides of every edge agree, so no crack is possible.
// Level-0 leaves still over the bound are counted (cdlod_sse_unmet_nodes). Its main parameter is a
// Knob, not ErrorBoundPx: the surplus metric bisects errbound (the one ErrorBoundPx scheme the
// harness looks up), and while morphing the bound is (1 + mu) tau, not tau.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "schemes/cdlod.h"
#include "schemes/preprocess/node_errors.h"
#include "shaders/cdlod_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

using namespace cdlod;
using glm::dvec2;
using glm::dvec3;

// node_cells = 0: Strugar's default grid of 32 (its seams need no range bound, so nothing ties n
// to the frame); quadrants of 16 x 16 cells (512 triangles) keep instances large enough for the
// GPU's instanced draws while the refinement stays fine-grained.
constexpr int kSseAutoCells = 32;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Refine by projected node error, balance 2:1, morph by the parent's error.
class SseLod : public NodeTree {
 public:
  SseLod(const Heightfield& hf, const Settings& s) : NodeTree(hf, s, {s.nodeCells > 0 ? s.nodeCells : kSseAutoCells}) {
    errors_ = cachedNodeErrors(hf, pyr_, s.cellsPerTexel);
    k_.resize(pyr_.nx.size());
    rho_.resize(pyr_.nx.size());
    for (size_t p = 0; p < pyr_.nx.size(); ++p) {
      k_[p].assign(flags_[p].size(), 0.0f);
      rho_[p].assign(flags_[p].size(), 0.0f);
    }
    leaves_.resize(pyr_.nx.size());
  }

 private:
  void selectNodes(const FrameUniforms& frame, Selection& out) const override {
    prepareScreenError(frame);
    selectSse(out);
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

  std::shared_ptr<const NodeErrors> errors_;
  mutable std::vector<std::vector<float>> k_, rho_;
  mutable std::vector<std::vector<NodeRef>> leaves_;
  mutable glm::dvec4 sides_[4];
  mutable glm::dmat4 view_{1};
  mutable double near_ = 0, offAxis_ = 1;
};

class CdlodSse : public Scheme {
 public:
  const SchemeInfo& info() const override {
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
          .front = {1, 2, 4},
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
  void validate(const ParamValues& v) const override { validateParams(info().name, v); }
  double targetAreaPx(const ParamValues&) const override { return 0.0; }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return std::make_unique<SseLod>(hf, settingsFrom(v, true));
  }
};

}  // namespace

const Scheme& cdlodSseScheme() {
  static const CdlodSse scheme;
  return scheme;
}

}  // namespace lb
