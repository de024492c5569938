#pragma once
// The surplus oracle (design.md section 6, "Surplus"): for one camera, the smallest uniform
// tessellation level per patch that meets a screen-space error bound, and the triangles that costs.
#include <cstdint>
#include <vector>

namespace lb {

struct Heightfield;
struct CameraMatrices;

struct OracleResult {
  uint64_t triangles = 0;   // sum of 2 L^2 over drawn (not culled) patches
  int patches = 0;          // drawn patches
  int saturated = 0;        // drawn patches where even level 64 misses the bound (they count as 64)
  std::vector<int> levels;  // per patch p = j * grid + i: L in [1, 64], 0 = culled
};

// For every patch of the uniform grid x grid base grid whose box (corner xz, height bounds from
// patchHeightBounds) is not entirely outside one plane of cam's frustum (the shaders' patchCulled),
// finds the smallest integer L in [1, 64] with error(L) <= boundPx, where error(L) is the largest
// pixel distance between the projections of (x, trueHeight, z) and (x, levelLSurface, z) over the
// heightfield samples (texel corners) inside the patch; width x height is the viewport in pixels.
//
// - The level-L surface is approximated by bilinear interpolation of the true heights at the
//   (L+1)^2 vertices of Vulkan's integer-spacing quad tessellation. The GPU's two triangles per
//   quad differ from that bilinear quad by at most a quarter of the quad's twist
//   |h00 - h10 - h01 + h11| / 4; the two coincide when the heights vary along one axis only.
// - Between texel corners the two bilinear surfaces are not compared (their difference can peak
//   where a vertex line crosses a texel line). A level whose vertices fall on every texel
//   (texels per patch an integer n <= 64, L a multiple of n) has zero error (to float rounding)
//   under this stand-in, so e.g. a 513^2 heightfield on a 32 grid never needs more than 16.
// - Only samples that can be seen count: a sample is skipped unless its true point or its level-L
//   point lies inside the view frustum (clip space, which also rejects points behind the camera).
//   The error map measures visible pixels only; off-screen samples just under a low camera would
//   otherwise blow up as w -> 0 and force level 64 where nothing is seen. A level-L point behind
//   the camera (w <= 0) while its true point is visible counts as an unbounded error.
// - error(L) is not monotone in L (a coarse grid can happen to hit a peak that a finer one
//   misses), so levels are scanned upward from 1 and the first one that meets the bound is
//   taken: the result is the exact minimum, not a bisection guess. A level fails at its first
//   sample over the bound, and the sample that failed last is tried first.
// boundPx >= 0; grid >= 1; width, height >= 1.
OracleResult surplusOracle(const Heightfield& hf, int grid, const CameraMatrices& cam, int width, int height,
                           double boundPx);

}  // namespace lb
