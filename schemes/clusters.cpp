// clusters: a Nanite-style cluster DAG for terrain (Karis, "Nanite: A Deep Dive", SIGGRAPH 2021
// Advances course; the open Vulkan references: nvpro-samples vk_lod_clusters, Bevy's virtual
// geometry): clusters of at most 128 triangles, groups of neighbouring clusters simplified to half
// with the group's outer border locked and split into the next level's clusters, drawn where the
// cut of the DAG crosses the screen-space error bound. Draw path: instanced grid
// (render/instanced.h), every cluster its own footprint in the one vertex and index buffer, one
// indexed draw per selected cluster; shader: shaders/clusters.vert (its vertex function,
// shaders/clusters_vertex.glsl, is the mesh twin's too: schemes/clusters_ms.cpp draws the same cut
// from this object's records and meshTable()). Design note: docs/draw-paths.md.
//
// Offline (schemes/preprocess/cluster_dag.h, cached by the terrain's heights, groups of a level
// simplified in parallel by meshoptimizer with meshopt_SimplifyLockBorder). Every constant is
// scale-free: 128 triangles a cluster, 4 clusters a group and half a group's triangles are counts;
// the simplifier sees lattice units and heights in sample spacings; errors are recorded in sample
// spacings (the exact vertical distance of a group's simplified triangles from the bilinear
// heightfield, raised to its inputs'); the one parameter, max_error_px, is in pixels. The same
// terrain at any world scale therefore gives the same DAG and the same cut.
//
// Cut (Nanite's rule): a cluster carries its own error and bounds (those of the group that made it)
// and its parent's (those of the group that simplifies it). A group is coarse enough when its
// error projects under the bound: rho = K e / D <= max_error_px, K = viewport height / (2
// tan(fovy / 2)), D the LOD eye's distance to the group's box (conservative: the box's nearest
// point). A cluster is drawn when the group that made it is coarse enough (or it is a finest
// cluster) and the group that simplifies it is not (or it is a root). Every cluster of a group
// reads the same group's test, so siblings decide alike, and errors rise and boxes grow up the DAG,
// so a group coarse enough has every group below it coarse enough: each place of the terrain is
// covered by exactly one simplification of it, whose borders were locked, and the cut is closed
// without stitching or skirts. Finest clusters drawn over the bound are counted
// (clusters_unmet_clusters); clusters whose own box is outside the LOD frustum are culled. As in
// chunked, D is a distance and not a view depth: a drawn cluster's error shows at most
// (1 + tan^2(fovx/2) + tan^2(fovy/2)) max_error_px (docs/draw-paths.md).
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "schemes/cdlod.h"
#include "schemes/preprocess/cluster_dag.h"
#include "shaders/clusters_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

using glm::dvec3;

class ClustersLod : public InstancedLod {
 public:
  ClustersLod(const Heightfield& hf, const ParamValues& v) : dag_(cachedClusterDag(hf)), tau_(v.at("max_error_px")) {
    cell_ = latticeCell(hf.extent, hf.width, hf.height, 1.0);
    for (const DagCluster& c : dag_->clusters)
      footprints_.push_back({"cluster" + std::to_string(footprints_.size()), c.vertices, c.indices});
    coarse_.resize(dag_->groups.size());
  }
  const std::vector<Footprint>& footprints() const override { return footprints_; }
  // clusters-ms's table (layout: shaders/clusters_params.h): the footprints, packed.
  std::vector<uint32_t> meshTable() const override {
    std::vector<uint32_t> words = {uint32_t(footprints_.size())};
    words.resize(1 + 3 * footprints_.size());
    for (size_t k = 0; k < footprints_.size(); ++k) {
      const Footprint& f = footprints_[k];
      words[1 + 3 * k] = uint32_t(words.size());
      for (const glm::vec2& v : f.vertices) words.push_back(uint32_t(v.x) | uint32_t(v.y) << 16);
      words[2 + 3 * k] = uint32_t(words.size());
      for (size_t i = 0; i < f.indices.size(); i += 3)
        words.push_back(f.indices[i] | f.indices[i + 1] << 8 | f.indices[i + 2] << 16);
      words[3 + 3 * k] = uint32_t(f.vertices.size()) | uint32_t(f.indices.size() / 3) << 16;
    }
    return words;
  }

  void select(const FrameUniforms& frame, Selection& out) const override {
    out.instances.resize(footprints_.size());
    for (auto& v : out.instances) v.clear();
    eye_ = dvec3(frame.lodEye);
    origin_ = glm::dvec2(frame.origin.x, frame.origin.y);
    glm::dvec4 planes[6];
    for (int i = 0; i < 6; ++i) planes[i] = glm::dvec4(frame.frustum[i]);
    K_ = 0.5 * double(frame.viewport.y) * std::abs(double(frame.lodProj[1][1]));
    for (size_t g = 0; g < coarse_.size(); ++g)
      coarse_[g] = screenError(dag_->groups[g].error, dag_->groups[g].box) <= tau_;
    long unmet = 0;
    for (size_t k = 0; k < dag_->clusters.size(); ++k) {
      const DagCluster& c = dag_->clusters[k];
      const bool fineEnough = c.madeBy < 0 || coarse_[size_t(c.madeBy)];
      const bool parentTooCoarse = c.group < 0 || !coarse_[size_t(c.group)];
      if (!fineEnough || !parentTooCoarse || cdlod::outsidePlanes(box(c.tight), planes)) continue;
      if (c.madeBy < 0 && screenError(c.error, c.bounds) > tau_) ++unmet;
      InstanceRecord r;
      r.a = glm::vec4(0.0f, float(c.level), float(k), 0.0f);
      out.instances[k].push_back(r);
    }
    out.counters = {double(unmet)};
  }

 private:
  cdlod::Box box(const DagBox& b) const {
    return {dvec3(origin_.x + b.lo.x * cell_.x, b.lo.y, origin_.y + b.lo.z * cell_.y),
            dvec3(origin_.x + b.hi.x * cell_.x, b.hi.y, origin_.y + b.hi.z * cell_.y)};
  }
  double screenError(float errorCells, const DagBox& b) const {
    if (errorCells <= 0.0f) return 0.0;
    const double d = std::sqrt(cdlod::boxDistance2(box(b), eye_));
    return d > 0 ? double(errorCells) * dag_->spacing * K_ / d : std::numeric_limits<double>::infinity();
  }

  std::shared_ptr<const ClusterDag> dag_;
  double tau_;
  glm::dvec2 cell_{1.0};
  std::vector<Footprint> footprints_;
  // Per-frame state: select() is const for its callers.
  mutable std::vector<char> coarse_;
  mutable dvec3 eye_{0.0};
  mutable glm::dvec2 origin_{0.0};
  mutable double K_ = 0;
};

class Clusters : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo{
        .name = "clusters",
        .description =
            "Nanite-style cluster DAG: 128-triangle clusters simplified in groups with locked borders, "
            "cut by projected error",
        .seed =
            "Karis 2021, Nanite: A Deep Dive (cluster groups simplified with locked borders, the DAG cut where "
            "a cluster's error projects under the bound and its parent's over)",
        .params = {{"max_error_px", LB_CLUSTERS_MAX_ERROR_PX, 2, 0.1, 64, false,
                    "draw a cluster once the error of the group that made it projects under this (pixels)"}},
        .mainParam = "max_error_px",
        .mainParamRole = MainParamRole::Knob,
        .front = {1, 2, 4},
        .path = DrawPath::InstancedGrid,
        .vert = "clusters",
        .counters = {{.frameKey = "clusters_unmet_clusters",
                      .caseKey = "clusters_unmet_frames",
                      .label = "frames with unmet bound"}},
    };
    return kInfo;
  }
  double targetAreaPx(const ParamValues&) const override { return 0.0; }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return std::make_unique<ClustersLod>(hf, v);
  }
};

}  // namespace

const Scheme& clustersScheme() {
  static const Clusters scheme;
  return scheme;
}

}  // namespace lb
