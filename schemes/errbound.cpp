// errbound: NOT from the seeds. The chunked-LOD / CDLOD idea (per-node precomputed geometric
// error, projected to the screen, refine until under a pixel budget) applied to hardware
// tessellation: a guaranteed maximum screen-space error with as few triangles as it can manage.
//
// Load time (CPU, schemes/preprocess/tess_deviation.cpp): per patch and per level 2^k, k = 0..6, the
// largest vertical distance dev(p, k) between the triangles the tessellator draws and the true
// bilinear heightfield, anywhere in the patch. The triangles are the reference tessellator's
// (integer partitioning): the transition strips next to finer edges for every power-of-two edge
// level >= 2^k, and every interior cell with both diagonals (so a device choosing the other one is
// covered). Between samples the difference of a bilinear cell and a plane peaks on the boundary
// of the cell-triangle piece, which is what triangleDeviation() scans.
//
// Why powers of two: a patch's triangles depend on its four edge levels, and errbound's edge
// level is the max of two patches' levels, i.e. any candidate level >= the patch's own. With
// powers of two that is at most 7 edge levels per level (28 level/edge pairs to precompute per
// edge); every integer level would be 2,080 pairs, each a full strip scan per patch. The price is
// granularity: a patch may get up to twice the level (4x the triangles) it strictly needs.
//
// Per frame, in the control shader (shaders/errbound.tesc) rather than in a compute pre-pass: the
// decision is 5 evaluations of one pure function of (patch, camera, table) per patch (its own
// level and its 4 neighbours' for the edges), needs no per-frame dispatch, barrier or buffer in
// the renderer, and keeps the timing frames the bare pipeline every scheme runs.
//
// The bound. The error pass (shaders/terrain.frag, LB_MODE_ERROR) measures, per pixel, the
// screen distance between the projections of the tessellated point P (the fragment's
// interpolated world position, on a drawn triangle) and the true point P' = (P.x, B(P.xz), P.z).
// For a vertical segment of length h the projection moves by h * K / w * |(u.x, u.y) - q u.w|
// along it (K = viewport height / (2 tan(fov/2)), w = view depth, u = world up in view space,
// q = screen position / K). errbound bounds this by dev(p, k) * K * S / w_min where
//  - dev(p, k) >= h: P and P' lie in the patch and P is on one of the scanned triangles;
//  - w_min <= w: the smallest view depth over the patch box (xz of the patch, heights of
//    patchHeightBounds, which contain both surfaces) clipped to each side plane of the frustum
//    and to the near plane (a visible fragment is inside all of them);
//  - S = max over the screen corners of |(u.x, u.y) - q u.w| >= the factor at any on-screen q
//    (the factor is convex in q). S is 1 for a level camera and at most sqrt(1 + |q|^2).
// The true point P' may be a hair off the fragment's q or depth (by the error itself, about
// max_error_px / K); that, float rounding on the GPU and the tessellator's 16-bit fixed-point
// vertex positions are what the test's 5% tolerance absorbs. Patches whose level 64 still misses
// the bound (camera very close to the ground) get 64 and are flagged in capture slot
// LB_ERRBOUND_CAPTURE_UNMET; measurement frames count them (errbound_unmet_patches).
#include <list>
#include <mutex>
#include <vector>

#include "render/scheme.h"
#include "schemes/preprocess/tess_deviation.h"
#include "shaders/errbound_params.h"
#include "shaders/shared.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

// tessDeviation costs seconds on a 3601^2 DEM; the surplus search and sweeps set the scheme
// many times on the same terrain, so the last few tables are kept (keyed by content, not address).
const DeviationTable& cachedDeviation(const Heightfield& hf, int grid) {
  struct Entry {
    int width, height, grid;
    float extent;
    uint64_t hash;
    DeviationTable table;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->grid == grid && it->extent == hf.extent &&
        it->hash == hash) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().table;
    }
  cache.push_front({hf.width, hf.height, grid, hf.extent, hash, tessDeviation(hf, grid)});
  if (cache.size() > 4) cache.pop_back();
  return cache.front().table;
}

class ErrBound : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "errbound",
        .description =
            "smallest power-of-two level per patch whose precomputed deviation stays under max_error_px on screen",
        .seed =
            "not from the seeds: chunked-LOD / CDLOD screen-space error bound applied to tessellation "
            "(docs/design.md, Schemes)",
        .params = {{"max_error_px", LB_ERRBOUND_MAX_ERROR_PX, 1, 0.1, 64, false,
                    "guaranteed maximum screen-space geometric error in pixels"}},
        .mainParam = "max_error_px",
        .mainParamRole = MainParamRole::ErrorBoundPx,
        .front = {1, 2, 4},
        .topology = Topology::Quad4,
        .partitioning = Partitioning::Integer,
        .tesc = "errbound",
        .tese = "terrain_quad",
        .culls = true,
        // Drawn patches whose level 64 still misses max_error_px (capture slot LB_ERRBOUND_CAPTURE_UNMET).
        .counters = {{.frameKey = "errbound_unmet_patches",
                      .caseKey = "errbound_unmet_frames",
                      .label = "frames with unmet bound"}},
    };
    return kInfo;
  }
  SchemeTexture preprocessGrid(const Heightfield& hf, const ParamValues&, int grid) const override {
    const DeviationTable& t = cachedDeviation(hf, grid);
    SchemeTexture tex{2 * grid, grid, std::vector<float>(size_t(grid) * size_t(grid) * 8, 0.0f)};
    for (int p = 0; p < grid * grid; ++p)
      for (int k = 0; k < kErrboundLevels; ++k) {
        int i = p % grid, j = p / grid;
        tex.rgba[(size_t(j) * size_t(2 * grid) + size_t(2 * i)) * 4 + size_t(k)] = t.at(p, k);
      }
    return tex;
  }
  std::vector<double> countFrame(const std::vector<float>& levels) const override {
    long unmet = 0;
    for (size_t i = 0; i + LB_CAPTURE_STRIDE <= levels.size(); i += LB_CAPTURE_STRIDE)
      unmet += levels[i + LB_ERRBOUND_CAPTURE_UNMET] > 0.5f;
    return {double(unmet)};
  }
};

}  // namespace

const Scheme& errBoundScheme() {
  static const ErrBound scheme;
  return scheme;
}

}  // namespace lb
