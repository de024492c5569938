#include "render/patch_grid.h"

#include <algorithm>
#include <cmath>

#include "terrain/heightfield.h"

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

std::vector<glm::vec2> patchHeightBounds(const Heightfield& hf, int n, Topology topology) {
  std::vector<glm::vec2> out;
  out.reserve(patchCountFor(n, topology));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Texel range covering the patch, widened by one so bilinear neighbours are included.
      int x0 = int(std::floor(float(i) / float(n) * float(hf.width - 1)));
      int x1 = int(std::ceil(float(i + 1) / float(n) * float(hf.width - 1)));
      int z0 = int(std::floor(float(j) / float(n) * float(hf.height - 1)));
      int z1 = int(std::ceil(float(j + 1) / float(n) * float(hf.height - 1)));
      float lo = INFINITY, hi = -INFINITY;
      for (int z = z0; z <= z1; ++z)
        for (int x = x0; x <= x1; ++x) {
          float h = hf.at(x, z);
          lo = std::min(lo, h);
          hi = std::max(hi, h);
        }
      out.emplace_back(lo, hi);
      if (topology == Topology::Tri3) out.emplace_back(lo, hi);
    }
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
