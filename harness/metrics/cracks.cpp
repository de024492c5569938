#include "metrics/cracks.h"

#include <stdexcept>

#include "metrics/edge_pattern.h"
#include "render/image_io.h"
#include "render/patch_grid.h"
#include "shaders/shared.h"

namespace lb {

bool patchDrawn(const std::vector<float>& levels, size_t patch, Topology topology) {
  const int outerCount = topology == Topology::Tri3 ? 3 : 4;
  for (int k = 0; k < outerCount; ++k)
    if (!(levels[patch * LB_CAPTURE_STRIDE + size_t(k)] > 0.0f)) return false;  // NaN counts as culled
  return true;
}

long gridCrackEdges(Topology topology, int grid, const std::vector<float>& levels) {
  const size_t n = size_t(grid);
  if (grid <= 0 || levels.size() < size_t(patchCountFor(grid, topology)) * LB_CAPTURE_STRIDE)
    throw std::invalid_argument("gridCrackEdges: fewer captured levels than grid patches");
  long cracks = 0;
  // One shared edge: patch a's outer level ea against patch b's outer level eb.
  auto compare = [&](size_t a, int ea, size_t b, int eb) {
    if (!patchDrawn(levels, a, topology) || !patchDrawn(levels, b, topology)) return;
    cracks += levels[a * LB_CAPTURE_STRIDE + size_t(ea)] != levels[b * LB_CAPTURE_STRIDE + size_t(eb)];
  };
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      const size_t q = j * n + i;
      if (topology == Topology::Tri3) {
        const size_t a = 2 * q, b = 2 * q + 1;
        compare(a, 1, b, 2);                               // diagonal 00-11
        if (i + 1 < n) compare(a, 0, 2 * (q + 1) + 1, 1);  // x = i+1: neighbour's 00-01
        if (j > 0) compare(a, 2, 2 * (q - n) + 1, 0);      // z = j: lower neighbour's 11-01
        continue;
      }
      if (i + 1 < n) compare(q, 2, q + 1, 0);  // u=1 of (i,j) is u=0 of (i+1,j)
      if (j + 1 < n) compare(q, 3, q + n, 1);  // v=1 of (i,j) is v=0 of (i,j+1)
    }
  return cracks;
}

long layoutCrackEdges(const PatchGeometry& geometry, const std::vector<float>& levels) {
  const size_t patches = geometry.indices.size() / 4;
  if (levels.size() < patches * LB_CAPTURE_STRIDE)
    throw std::invalid_argument("layoutCrackEdges: fewer captured levels than layout patches");
  auto drawn = [&](const PatchSide& s) { return patchDrawn(levels, s.patch, Topology::Quad4); };
  auto level = [&](const PatchSide& s) { return levels[s.patch * LB_CAPTURE_STRIDE + size_t(s.side)]; };
  QuadEdges edges = quadPatchEdges(geometry);
  long cracks = 0;
  for (const auto& [a, b] : edges.equal) cracks += drawn(a) && drawn(b) && level(a) != level(b);
  for (const HalfBoundary& h : edges.half) {
    if (!drawn(h.large)) continue;
    bool loCrack = drawn(h.lo) && !fractionalEvenHalfMatches(level(h.large), level(h.lo), 0);
    bool hiCrack = drawn(h.hi) && !fractionalEvenHalfMatches(level(h.large), level(h.hi), 1);
    cracks += loCrack || hiCrack;
  }
  return cracks;
}

long analyticCracks(const Scheme& scheme, const ParamValues& params, const Heightfield& terrain, int grid,
                    const std::vector<float>& levels) {
  if (scheme.info().path != DrawPath::Tessellation)
    throw std::logic_error("analyticCracks: '" + scheme.info().name +
                           "' draws no patches; its cracks come from the drawn mesh (metrics/mesh_cracks.h)");
  PatchGeometry layout = scheme.patchLayout(terrain, params, grid);
  return layout.indices.empty() ? gridCrackEdges(scheme.info().topology, grid, levels)
                                : layoutCrackEdges(layout, levels);
}

RgbaImage crackMaskImage(const RgbaImage& frame, const std::vector<uint8_t>& mask) {
  const size_t n = size_t(frame.width) * size_t(frame.height);
  if (frame.px.size() != n * 4 || mask.size() != n)
    throw std::invalid_argument("crackMaskImage: frame and mask sizes differ");
  RgbaImage out = frame;
  for (size_t i = 0; i < n; ++i) {
    uint8_t* p = &out.px[i * 4];
    if (mask[i]) {
      p[0] = 255, p[1] = 0, p[2] = 0;
    } else {
      for (int c = 0; c < 3; ++c) p[c] = uint8_t(p[c] / 3);  // dimmed: the red stands out everywhere
    }
    p[3] = 255;
  }
  return out;
}

void writeCrackMaskPng(const std::string& path, const RgbaImage& frame, const std::vector<uint8_t>& mask) {
  RgbaImage img = crackMaskImage(frame, mask);
  writePng(path, img.width, img.height, img.px);
}

}  // namespace lb
