// chunked: T. Ulrich, "Rendering Massive Terrains using Chunked Level of Detail Control" (SIGGRAPH
// 2002 course), as GIS and globe renderers ship it (Cesium's terrain tiles and their screen-space
// error): a quadtree of chunks whose meshes were simplified offline to a geometric error that
// doubles per level, chosen per frame by projected error and sealed by skirts. Draw path: instanced
// grid (render/instanced.h), every chunk its own footprint drawn once (one indexed draw per
// selected chunk); shader: shaders/chunked.vert. Design note: docs/draw-paths.md.
//
// Offline (schemes/preprocess/chunk_tree.h, cached by the terrain's heights): level-l chunks of
// leaf_cells * 2^l sample spacings a side, each simplified by a restricted quadtree to the target
// error e_l = e_0 2^l, e_0 = leaf_error sample spacings (scale-free), its recorded error delta the
// exact largest vertical distance of its triangles from the bilinear heightfield, raised to its
// children's. Skirts below every interior chunk side reach a bottom line all chunks share, so the
// drawn mesh is closed wherever neighbours of any levels meet.
//
// Selection: Ulrich's rule, rho = K delta / D with K = viewport height / (2 tan(fovy / 2)) (his W and
// horizontal FOV, Cesium's height and vertical FOV: the same for square pixels) and D the distance
// from the LOD eye to the chunk's box; a chunk is drawn when rho <= max_error_px or it is a leaf,
// else its children are visited; boxes outside the LOD frustum are culled. Finest chunks drawn over
// the bound are counted (chunked_unmet_chunks). D is a distance, not a view depth, and a vertical
// error seen off the view axis projects longer: on screen the error of a drawn chunk is at most
// (1 + tan^2(fovx/2) + tan^2(fovy/2)) max_error_px (docs/draw-paths.md derives it).
//
// Geomorphing, Ulrich's option, is not implemented: morphing a chunk's vertices towards its parent's
// surface needs each vertex's height on the parent mesh and a morph factor per chunk; popping is
// measured instead (the popping pass), and crack-freedom does not depend on it here.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "error.h"
#include "number_text.h"
#include "schemes/cdlod.h"
#include "schemes/preprocess/chunk_tree.h"
#include "shaders/chunked_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

using glm::dvec3;

class ChunkedLod : public InstancedLod {
 public:
  ChunkedLod(const Heightfield& hf, const ParamValues& v)
      : tree_(cachedChunkTree(hf, int(v.at("leaf_cells")), v.at("leaf_error"))), tau_(v.at("max_error_px")) {
    cell_ = latticeCell(hf.extent, hf.width, hf.height, 1.0);
    for (const Chunk& c : tree_->chunks)
      footprints_.push_back({"chunk" + std::to_string(footprints_.size()), c.mesh.vertices, c.mesh.indices});
  }
  const std::vector<Footprint>& footprints() const override { return footprints_; }

  void select(const FrameUniforms& frame, Selection& out) const override {
    out.instances.resize(footprints_.size());
    for (auto& v : out.instances) v.clear();
    eye_ = dvec3(frame.lodEye);
    origin_ = glm::dvec2(frame.origin.x, frame.origin.y);
    for (int i = 0; i < 6; ++i) planes_[i] = glm::dvec4(frame.frustum[i]);
    K_ = 0.5 * double(frame.viewport.y) * std::abs(double(frame.lodProj[1][1]));
    unmet_ = skirt_ = 0;
    visit(out, tree_->root);
    out.counters = {double(unmet_), double(skirt_)};
  }

 private:
  cdlod::Box box(const Chunk& c, double below) const {
    return {dvec3(origin_.x + c.x0 * cell_.x, double(c.hmin) - below, origin_.y + c.z0 * cell_.y),
            dvec3(origin_.x + c.x1 * cell_.x, double(c.hmax), origin_.y + c.z1 * cell_.y)};
  }
  double screenError(const Chunk& c) const {
    if (c.error <= 0.0f) return 0.0;
    const double d = std::sqrt(cdlod::boxDistance2(box(c, 0.0), eye_));
    return d > 0 ? double(c.error) * K_ / d : std::numeric_limits<double>::infinity();
  }
  void visit(Selection& out, int k) const {
    const Chunk& c = tree_->chunks[size_t(k)];
    if (cdlod::outsidePlanes(box(c, double(tree_->skirtDepth)), planes_)) return;
    const double rho = screenError(c);
    const bool leaf = c.level == 0;
    if (rho > tau_ && !leaf) {
      for (int ch : c.children)
        if (ch >= 0) visit(out, ch);
      return;
    }
    if (rho > tau_) ++unmet_;
    skirt_ += c.skirtTriangles;
    InstanceRecord r;
    r.a = glm::vec4(tree_->skirtDepth, float(c.level), 0.0f, 0.0f);
    out.instances[size_t(k)].push_back(r);
  }

  std::shared_ptr<const ChunkTree> tree_;
  double tau_;
  glm::dvec2 cell_{1.0};
  std::vector<Footprint> footprints_;
  // Per-frame state: select() is const for its callers.
  mutable dvec3 eye_{0.0};
  mutable glm::dvec2 origin_{0.0};
  mutable glm::dvec4 planes_[6];
  mutable double K_ = 0;
  mutable long unmet_ = 0, skirt_ = 0;
};

class Chunked : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo{
        .name = "chunked",
        .description = "chunked LOD: offline-simplified quadtree chunks with skirts, chosen by projected error",
        .seed =
            "Ulrich 2002, Rendering Massive Terrains using Chunked Level of Detail Control (rho = K delta / D, "
            "skirts); Cesium's screen-space error",
        .params = {{"max_error_px", LB_CHUNKED_MAX_ERROR_PX, 2, 0.1, 64, false,
                    "draw a chunk once its geometric error projects under this (pixels)"},
                   {"leaf_cells", LB_CHUNKED_LEAF_CELLS, 32, 8, 256, true,
                    "sample spacings a side of the finest chunks (a power of two)"},
                   {"leaf_error", LB_CHUNKED_LEAF_ERROR, 0.1, 0.001, 10, false,
                    "target geometric error of the finest chunks in sample spacings; doubles per level"}},
        .mainParam = "max_error_px",
        .mainParamRole = MainParamRole::Knob,
        .front = {1, 2, 4},
        .path = DrawPath::InstancedGrid,
        .vert = "chunked",
        .counters = {{.frameKey = "chunked_unmet_chunks",
                      .caseKey = "chunked_unmet_frames",
                      .label = "frames with unmet bound"},
                     {.frameKey = "chunked_skirt_triangles",
                      .caseKey = "chunked_skirt_frames",
                      .label = "frames drawing skirts"}},
    };
    return kInfo;
  }
  void validate(const ParamValues& v) const override {
    if (!cdlod::isPowerOfTwo(v.at("leaf_cells")))
      throw InputError("chunked: leaf_cells must be a power of two (got " + numberText(v.at("leaf_cells")) + ")");
  }
  double targetAreaPx(const ParamValues&) const override { return 0.0; }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield& hf, const ParamValues& v) const override {
    return std::make_unique<ChunkedLod>(hf, v);
  }
};

}  // namespace

const Scheme& chunkedScheme() {
  static const Chunked scheme;
  return scheme;
}

}  // namespace lb
