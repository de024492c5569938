#include "metrics/edge_pattern.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace lb {

PatchRect patchRect(const PatchGeometry& g, size_t patch) {
  glm::vec2 c0 = g.vertices[g.indices[patch * 4]], c2 = g.vertices[g.indices[patch * 4 + 2]];
  return {c0.x, c0.y, c2.x, c2.y};
}

EdgeKey patchSide(const PatchRect& r, int side) {
  switch (side) {
    case 0:
      return {1, r.x0, r.z0, r.z1};
    case 1:
      return {0, r.z0, r.x0, r.x1};
    case 2:
      return {1, r.x1, r.z0, r.z1};
    default:
      return {0, r.z1, r.x0, r.x1};
  }
}

QuadEdges quadPatchEdges(const PatchGeometry& g) {
  const size_t n = g.indices.size() / 4;
  std::map<EdgeKey, std::vector<PatchSide>> edges;
  for (size_t p = 0; p < n; ++p)
    for (int s = 0; s < 4; ++s) edges[patchSide(patchRect(g, p), s)].push_back({p, s});
  QuadEdges out;
  for (const auto& [key, sides] : edges) {
    if (sides.size() > 2) throw std::logic_error("quadPatchEdges: a patch side is shared by more than two patches");
    if (sides.size() == 2) out.equal.push_back({sides[0], sides[1]});
    auto [axis, fixed, a, b] = key;
    float mid = 0.5f * (a + b);
    auto lo = edges.find({axis, fixed, a, mid}), hi = edges.find({axis, fixed, mid, b});
    if (lo == edges.end() || hi == edges.end()) continue;
    // The large side belongs to one patch, each half to one smaller patch on the other side.
    if (sides.size() != 1 || lo->second.size() != 1 || hi->second.size() != 1)
      throw std::logic_error("quadPatchEdges: a half-size boundary is shared by more than two patches");
    out.half.push_back({sides[0], lo->second[0], hi->second[0]});
  }
  return out;
}

// Vulkan spec, "Tessellator Spacing", fractional_even_spacing: the level is clamped to [2, 64] and
// rounded up to the nearest even integer n; the edge is cut into n - 2 equal segments and two
// shorter equal ones, placed symmetrically, whose length falls monotonically with n - f (equal to
// the others at n - f = 0). With segments of 1/f the two short ones are (f - n + 2) / (2 f) each.
// Their placement is implementation-dependent; here they meet at the middle (new vertices grow out
// of the centre).
std::vector<double> fractionalEvenVertices(double level) {
  double f = std::clamp(level, 2.0, 64.0);
  int n = 2 * int(std::ceil(f / 2.0));
  double full = 1.0 / f, part = (f - (n - 2)) / (2.0 * f);
  std::vector<double> segments(size_t(n - 2) / 2, full);
  segments.push_back(part);
  segments.push_back(part);
  segments.insert(segments.end(), size_t(n - 2) / 2, full);
  std::vector<double> v{0.0};
  for (double s : segments) v.push_back(v.back() + s);
  v.back() = 1.0;
  return v;
}

constexpr double kParamEps = 1e-9;

bool fractionalEvenHalfMatches(double large, double small, int half) {
  const double lo = 0.5 * half, hi = lo + 0.5;
  std::vector<double> a;
  for (double t : fractionalEvenVertices(large))
    if (t > lo - kParamEps && t < hi + kParamEps) a.push_back(t);
  std::vector<double> b;
  for (double t : fractionalEvenVertices(small)) b.push_back(lo + 0.5 * t);
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > kParamEps) return false;
  return true;
}

bool fractionalEvenPatternsMatch(double large, double smallLo, double smallHi) {
  return fractionalEvenHalfMatches(large, smallLo, 0) && fractionalEvenHalfMatches(large, smallHi, 1);
}

}  // namespace lb
