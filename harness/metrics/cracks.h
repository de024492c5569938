#pragma once
// Crack metrics (docs/design.md, What is measured): (a) analytic, from the tessellation levels the
// control shader captured; (b) in the image, against the crack-free `reference` rendering.
#include <cstdint>
#include <string>
#include <vector>

#include "metrics/image_metrics.h"
#include "render/scheme.h"

namespace lb {

struct Heightfield;

// A patch is drawn unless one of its domain's outer levels is <= 0 or NaN (Vulkan discards such a
// patch); culling shaders write all zeros. `patch` indexes LB_CAPTURE_STRIDE floats per patch.
bool patchDrawn(const std::vector<float>& levels, size_t patch, Topology topology);

// Shared edges of the renderer's uniform grid (RenderSettings::grid = n, patch p = j * n + i;
// Tri3: patches 2q and 2q + 1 of quad q) whose two patches output different levels for the edge
// (exact float compare: stricter than what the tessellator can show, e.g. integer 3.2 vs 3.7),
// counting only edges whose patches are both drawn. A drawn patch next to a culled one is no
// crack on screen: culling is conservative, so the culled side lies wholly outside the frustum.
// Quad4/Quad12: (i,j)-(i+1,j) compares p.outer[2] with q.outer[0], (i,j)-(i,j+1) p.outer[3] with
// q.outer[1]. Tri3 (outer[k] is the edge opposite corner k; A = (00,10,11), B = (00,11,01)): the
// diagonal A.outer[1] with B.outer[2] of the same quad, the edge x = i+1 A.outer[0] with
// B.outer[1] of quad (i+1,j), the edge z = j A.outer[2] with B.outer[0] of quad (i,j-1).
// Throws std::invalid_argument when `levels` holds fewer than patchCountFor(n) patches.
long gridCrackEdges(Topology topology, int grid, const std::vector<float>& levels);

// Shared edges of a Quad4 layout from Scheme::patchGeometry (square patches on an exact lattice,
// fractional_even partitioning) that show different vertices on the two sides: an edge between
// two equal-size drawn patches whose levels differ (exact compare), and each boundary where a large
// edge meets two half-size edges whose vertices (metrics/edge_pattern.h) differ on a half whose
// small patch is drawn (the large patch drawn too); such a boundary counts once.
long layoutCrackEdges(const PatchGeometry& geometry, const std::vector<float>& levels);

// The analytic crack count of one frame: layoutCrackEdges on Scheme::patchLayout when the scheme
// has its own patch layout, otherwise gridCrackEdges(topology, grid, levels). `levels` is
// Renderer::capturedLevels() after a capture pass (renderImage) of that frame; `grid` the
// renderer's RenderSettings::grid.
long analyticCracks(const Scheme& scheme, const ParamValues& params, const Heightfield& terrain, int grid,
                    const std::vector<float>& levels);

// Image cracks are crackPixels(schemeImage, referenceImage, &mask) (metrics/image_metrics.h),
// the reference image being the `reference` scheme's rendering of the same pose and settings.
// Mask image: the frame dimmed to a third, crack pixels (mask != 0) pure red.
RgbaImage crackMaskImage(const RgbaImage& frame, const std::vector<uint8_t>& mask);
// Writes crackMaskImage as PNG (atomically, render/image_io.h).
void writeCrackMaskPng(const std::string& path, const RgbaImage& frame, const std::vector<uint8_t>& mask);

}  // namespace lb
