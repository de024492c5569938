#include "render/patch_grid.h"

#include <algorithm>
#include <cmath>

#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

std::vector<glm::vec2> gridVertices(int n, float extent) {
  std::vector<glm::vec2> v;
  v.reserve(size_t(n + 1) * size_t(n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.emplace_back(extent * float(i) / float(n), extent * float(j) / float(n));
  return v;
}

uint32_t controlPointCount(Topology t) {
  return t == Topology::Quad12 ? 12 : t == Topology::Tri3 ? 3 : 4;
}

uint32_t patchCountFor(int n, Topology t) {
  return uint32_t(n * n) * (t == Topology::Tri3 ? 2u : 1u);
}

std::vector<uint32_t> patchIndices(int n, Topology topology) {
  auto v = [n](int i, int j) {
    i = std::clamp(i, 0, n);
    j = std::clamp(j, 0, n);
    return uint32_t(j * (n + 1) + i);
  };
  std::vector<uint32_t> idx;
  idx.reserve(size_t(patchCountFor(n, topology)) * controlPointCount(topology));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (topology == Topology::Tri3) {
        idx.insert(idx.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1)});
        idx.insert(idx.end(), {v(i, j), v(i + 1, j + 1), v(i, j + 1)});
        continue;
      }
      idx.insert(idx.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      if (topology == Topology::Quad12)
        idx.insert(idx.end(), {v(i - 1, j), v(i - 1, j + 1), v(i, j - 1), v(i + 1, j - 1), v(i + 2, j), v(i + 2, j + 1),
                               v(i, j + 2), v(i + 1, j + 2)});
    }
  return idx;
}

PatchGeometry drawnPatches(const Scheme& scheme, const ParamValues& params, const Heightfield& hf, int n) {
  const Topology topo = scheme.info().topology;
  PatchGeometry g = scheme.patchGeometry(hf, params, n);
  if (g.vertices.empty()) {
    g.vertices = gridVertices(n, hf.extent);
    g.indices = patchIndices(n, topo);
    g.bounds = patchHeightBounds(hf, n, topo);
  }
  // Schemes lay patches out terrain-locally; the terrain's origin moves them into the world, in
  // double and then rounded to float, as an engine without camera-relative coordinates would.
  if ((hf.originX != 0.0 || hf.originZ != 0.0) && !g.schemeUnits)
    for (glm::vec2& v : g.vertices) v = glm::vec2(float(double(v.x) + hf.originX), float(double(v.y) + hf.originZ));
  return g;
}

std::vector<glm::vec2> patchHeightBounds(const Heightfield& hf, int n, Topology topology) {
  // Every patch renderer computes these (a tuned search builds dozens), and at 16385^2 a
  // single-threaded scan of every sample took about a second: patch rows run in parallel, each
  // writing only its own entries, so the result does not depend on the thread count.
  const int perPatch = topology == Topology::Tri3 ? 2 : 1;
  std::vector<glm::vec2> out(size_t(n) * size_t(n) * size_t(perPatch));
  // Bands of at least 1M samples: small terrains (the tests') stay on one thread.
  const long long samplesPerRow = (long long)hf.width * std::max(1, hf.height / std::max(1, n));
  const int rowsPerBand = int(std::max(1LL, (1LL << 20) / std::max(1LL, samplesPerRow)));
  parallelRows(
      n,
      [&](int j0, int j1) {
        for (int j = j0; j < j1; ++j)
          for (int i = 0; i < n; ++i) {
            // Texel range covering the patch, widened by one so bilinear neighbours are included.
            const int x0 = int(std::floor(float(i) / float(n) * float(hf.width - 1)));
            const int x1 = std::min(hf.width - 1, int(std::ceil(float(i + 1) / float(n) * float(hf.width - 1))));
            const int z0 = int(std::floor(float(j) / float(n) * float(hf.height - 1)));
            const int z1 = std::min(hf.height - 1, int(std::ceil(float(j + 1) / float(n) * float(hf.height - 1))));
            float lo = INFINITY, hi = -INFINITY;
            for (int z = z0; z <= z1; ++z) {
              const float* row = hf.h.data() + size_t(z) * size_t(hf.width);
              for (int x = x0; x <= x1; ++x) {
                lo = std::min(lo, row[x]);
                hi = std::max(hi, row[x]);
              }
            }
            const size_t k = (size_t(j) * size_t(n) + size_t(i)) * size_t(perPatch);
            for (int p = 0; p < perPatch; ++p) out[k + size_t(p)] = glm::vec2(lo, hi);
          }
      },
      rowsPerBand);
  return out;
}

glm::vec2 rectHeightBounds(const Heightfield& hf, glm::vec2 lo, glm::vec2 hi) {
  // Texel range covering the rectangle, floor/ceil so bilinear neighbours are included, then clamped.
  auto texel = [&hf](float world, int size, bool up) {
    float t = std::clamp(world / hf.extent * float(size - 1), 0.0f, float(size - 1));
    return int(up ? std::ceil(t) : std::floor(t));
  };
  int x0 = texel(lo.x, hf.width, false), x1 = texel(hi.x, hf.width, true);
  int z0 = texel(lo.y, hf.height, false), z1 = texel(hi.y, hf.height, true);
  glm::vec2 out(INFINITY, -INFINITY);
  for (int z = z0; z <= z1; ++z)
    for (int x = x0; x <= x1; ++x) {
      float h = hf.at(x, z);
      out = glm::vec2(std::min(out.x, h), std::max(out.y, h));
    }
  return out;
}

}  // namespace lb
