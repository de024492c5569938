#include "metrics/mesh_cracks.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace lb {

namespace {

// An undirected edge: its two endpoints' bit patterns (x, y, z each), the lexicographically
// smaller endpoint first, so both triangles using the edge produce the same six words.
struct EdgeKey {
  uint32_t w[6];
  bool operator==(const EdgeKey& o) const { return std::memcmp(w, o.w, sizeof w) == 0; }
};

// Bit pattern with -0 read as +0: equal values that two expressions might round to either zero
// must still pair.
uint32_t canonicalBits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u == 0x80000000u ? 0u : u;
}

float bitsToFloat(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

uint64_t edgeHash(const EdgeKey& e) {
  auto word = [&](int i) { return uint64_t(e.w[2 * i]) | uint64_t(e.w[2 * i + 1]) << 32; };
  return mix64(word(0) ^ mix64(word(1) ^ mix64(word(2) + 0x9e3779b97f4a7c15ull)));
}

// An edge and its hash. A canonical bit pattern is never all ones (that is a NaN, skipped), so
// w[0] == emptyWord marks an empty cache slot.
struct EdgeRecord {
  EdgeKey key;
  uint64_t hash;
};
constexpr uint32_t emptyWord = 0xffffffffu;

struct Vertex {
  uint32_t bits[3];
};

bool sameVertex(const Vertex& a, const Vertex& b) {
  return a.bits[0] == b.bits[0] && a.bits[1] == b.bits[1] && a.bits[2] == b.bits[2];
}

EdgeKey makeEdge(const Vertex& a, const Vertex& b) {
  const bool aFirst = std::lexicographical_compare(a.bits, a.bits + 3, b.bits, b.bits + 3);
  const Vertex& lo = aFirst ? a : b;
  const Vertex& hi = aFirst ? b : a;
  EdgeKey e;
  std::memcpy(e.w, lo.bits, sizeof lo.bits);
  std::memcpy(e.w + 3, hi.bits, sizeof hi.bits);
  return e;
}

// An open interior edge projected to xz, in double: the predicates below then add almost no
// rounding of their own to what the floats carry.
struct Segment {
  double ax, az, bx, bz, len;
};

// Collinear in xz (both endpoints of the shorter within tol of the longer's line) with an overlap
// longer than tol: segments that merely touch at a shared vertex overlap by ~0 and do not count.
bool overlapsCollinear(const Segment& e, const Segment& f, double tol) {
  if (std::min(e.ax, e.bx) > std::max(f.ax, f.bx) + tol || std::min(f.ax, f.bx) > std::max(e.ax, e.bx) + tol ||
      std::min(e.az, e.bz) > std::max(f.az, f.bz) + tol || std::min(f.az, f.bz) > std::max(e.az, e.bz) + tol)
    return false;
  const Segment& r = e.len >= f.len ? e : f;
  const Segment& s = e.len >= f.len ? f : e;
  const double dx = (r.bx - r.ax) / r.len, dz = (r.bz - r.az) / r.len;
  auto dist = [&](double px, double pz) { return std::abs(dx * (pz - r.az) - dz * (px - r.ax)); };
  if (dist(s.ax, s.az) > tol || dist(s.bx, s.bz) > tol) return false;
  const double t0 = dx * (s.ax - r.ax) + dz * (s.az - r.az);
  const double t1 = dx * (s.bx - r.ax) + dz * (s.bz - r.az);
  return std::min(std::max(t0, t1), r.len) - std::max(std::min(t0, t1), 0.0) > tol;
}

size_t findRoot(std::vector<uint32_t>& parent, size_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

MeshCrackResult meshCracks(const std::vector<glm::vec3>& triangleVertices, const MeshCrackBounds& terrainBorder) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be packed");
  return meshCracks(triangleVertices.empty() ? nullptr : &triangleVertices[0].x, triangleVertices.size(), 3,
                    terrainBorder);
}

MeshCrackResult meshCracks(const float* vertices, size_t vertexCount, size_t strideFloats,
                           const MeshCrackBounds& border) {
  if (vertexCount % 3 != 0) throw std::invalid_argument("meshCracks: vertex count is not a multiple of 3");
  if (vertexCount > 0 && (vertices == nullptr || strideFloats < 3))
    throw std::invalid_argument("meshCracks: vertex stride is under 3 floats");
  const glm::vec2 lo = border.min, hi = border.max;
  if (!std::isfinite(lo.x) || !std::isfinite(lo.y) || !std::isfinite(hi.x) || !std::isfinite(hi.y) || !(hi.x > lo.x) ||
      !(hi.y > lo.y))
    throw std::invalid_argument("meshCracks: the terrain border is not a finite rectangle of positive size");

  MeshCrackResult out;
  const double magnitude = std::max({std::abs(double(lo.x)), std::abs(double(hi.x)), std::abs(double(lo.y)),
                                     std::abs(double(hi.y)), double(hi.x) - lo.x, double(hi.y) - lo.y});
  const double tol = 8.0 * FLT_EPSILON * magnitude;
  out.tolerance = tol;

  const size_t triangleCount = vertexCount / 3;
  out.triangles = long(triangleCount);

  // Parity count. A single hash table over millions of edges would miss the cache on almost every
  // probe. Most edges pair within a few hundred triangles (inside one instance, one row of a
  // footprint), so a direct-mapped cache of edges seen an odd number of times cancels them on the
  // spot; what it evicts, and what is left in it at the end, is paired exactly afterwards.
  constexpr size_t cacheSize = size_t(1) << 16;
  std::vector<EdgeRecord> cache(cacheSize);
  for (EdgeRecord& r : cache) r.key.w[0] = emptyWord;
  std::vector<EdgeRecord> rest;
  auto addEdge = [&](const Vertex& a, const Vertex& b) {
    EdgeRecord e{makeEdge(a, b), 0};
    e.hash = edgeHash(e.key);
    EdgeRecord& slot = cache[e.hash & (cacheSize - 1)];
    if (slot.key == e.key) {
      slot.key.w[0] = emptyWord;
      return;
    }
    if (slot.key.w[0] != emptyWord) rest.push_back(slot);
    slot = e;
  };
  auto readVertex = [&](size_t v, Vertex& vertex) {
    const float* p = vertices + v * strideFloats;
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p[c])) return false;
      vertex.bits[c] = canonicalBits(p[c]);
    }
    return true;
  };
  const double tol2 = tol * tol;
  for (size_t t = 0; t < triangleCount; ++t) {
    Vertex v[3];
    if (!readVertex(3 * t, v[0]) || !readVertex(3 * t + 1, v[1]) || !readVertex(3 * t + 2, v[2])) {
      ++out.invalidTriangles;  // the GPU draws nothing defined: skipped whole
      continue;
    }
    const bool e01 = sameVertex(v[0], v[1]), e12 = sameVertex(v[1], v[2]), e20 = sameVertex(v[2], v[0]);
    if (e01 || e12 || e20) {
      ++out.collapsedTriangles;
      ++out.degenerateTriangles;
    } else {
      // Zero xz area up to tol: the third vertex within tol of the longest side's line.
      double x[3], z[3];
      for (int k = 0; k < 3; ++k) x[k] = bitsToFloat(v[k].bits[0]), z[k] = bitsToFloat(v[k].bits[2]);
      double longest2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double dx = x[(k + 1) % 3] - x[k], dz = z[(k + 1) % 3] - z[k];
        longest2 = std::max(longest2, dx * dx + dz * dz);
      }
      const double twiceArea = (x[1] - x[0]) * (z[2] - z[0]) - (z[1] - z[0]) * (x[2] - x[0]);
      out.degenerateTriangles += twiceArea * twiceArea <= tol2 * longest2;
    }
    if (!e01) addEdge(v[0], v[1]);
    if (!e12) addEdge(v[1], v[2]);
    if (!e20) addEdge(v[2], v[0]);
  }
  for (const EdgeRecord& r : cache)
    if (r.key.w[0] != emptyWord) rest.push_back(r);
  cache = {};

  // The rest: sorted in place by the top bits of the hash into partitions of ~8k edges, each paired
  // in a small table that stays in cache. Table slots use middle bits, independent of both the
  // partition's and the cache's.
  int partitionBits = 0;
  while (partitionBits < 16 && (rest.size() >> partitionBits) > 8192) ++partitionBits;
  const size_t partitions = size_t(1) << partitionBits;
  auto partitionOf = [&](const EdgeRecord& r) {
    return partitionBits == 0 ? size_t(0) : size_t(r.hash >> (64 - partitionBits));
  };
  std::vector<size_t> start(partitions + 1, 0);
  for (const EdgeRecord& r : rest) ++start[partitionOf(r) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  {
    std::vector<size_t> next(start.begin(), start.end() - 1);
    for (size_t p = 0; p < partitions; ++p)
      while (next[p] < start[p + 1]) {
        const size_t q = partitionOf(rest[next[p]]);
        if (q == p) {
          ++next[p];
        } else {
          std::swap(rest[next[p]], rest[next[q]++]);
        }
      }
  }
  std::vector<EdgeKey> open;
  std::vector<uint32_t> table;
  std::vector<uint8_t> odd;
  for (size_t p = 0; p < partitions; ++p) {
    const size_t first = start[p], n = start[p + 1] - first;
    if (n == 0) continue;
    size_t size = 16;
    while (size < 2 * n) size *= 2;
    const size_t mask = size - 1;
    table.assign(size, 0);  // index + 1 of the first record of each edge; 0 = empty
    odd.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
      const EdgeRecord& e = rest[first + i];
      for (size_t slot = size_t(e.hash >> 20) & mask;; slot = (slot + 1) & mask) {
        if (table[slot] == 0) {
          table[slot] = uint32_t(i + 1);
          odd[i] = 1;
          break;
        }
        if (rest[first + table[slot] - 1].key == e.key) {
          odd[table[slot] - 1] ^= 1;
          break;
        }
      }
    }
    for (size_t i = 0; i < n; ++i)
      if (odd[i]) open.push_back(rest[first + i].key);
  }
  rest = {};
  out.openEdges = long(open.size());

  // Border edges out; interior ones of (near) zero xz length can overlap nothing.
  auto onLine = [&](float v, float c) { return std::abs(double(v) - double(c)) <= tol; };
  std::vector<Segment> segments;
  for (const EdgeKey& e : open) {
    const float ax = bitsToFloat(e.w[0]), az = bitsToFloat(e.w[2]);
    const float bx = bitsToFloat(e.w[3]), bz = bitsToFloat(e.w[5]);
    if ((onLine(ax, lo.x) && onLine(bx, lo.x)) || (onLine(ax, hi.x) && onLine(bx, hi.x)) ||
        (onLine(az, lo.y) && onLine(bz, lo.y)) || (onLine(az, hi.y) && onLine(bz, hi.y))) {
      ++out.borderEdges;
      continue;
    }
    const double len = std::sqrt((double(bx) - ax) * (double(bx) - ax) + (double(bz) - az) * (double(bz) - az));
    if (len <= tol) {
      ++out.unpairedEdges;
      continue;
    }
    segments.push_back({ax, az, bx, bz, len});
  }
  open = {};
  if (segments.empty()) return out;

  // Candidate pairs through a uniform xz grid of cell h = the median open length: each segment is
  // listed in every cell its tol-dilated pieces (each at most h long) touch, so two segments that
  // overlap by more than tol share a cell. h grows so that no segment has more than 1024 pieces.
  double h;
  {
    std::vector<double> lengths(segments.size());
    double longest = 0.0;
    for (size_t i = 0; i < segments.size(); ++i) lengths[i] = segments[i].len, longest = std::max(longest, lengths[i]);
    std::nth_element(lengths.begin(), lengths.begin() + long(lengths.size() / 2), lengths.end());
    h = std::max({lengths[lengths.size() / 2], longest / 1024.0, 4.0 * tol});
  }
  auto cellOf = [&](double v, double origin) {
    return int64_t(std::clamp(std::floor((v - origin) / h), -2.0e9, 2.0e9)) + (int64_t(1) << 31);
  };
  // Cells go to hash buckets by counting sort (no comparison sort); two cells sharing a bucket only
  // cost pair tests, which are geometric.
  std::vector<std::pair<uint32_t, uint32_t>> listed;  // (bucket, segment)
  std::vector<uint64_t> mine;
  int bucketBits = 4;
  while (bucketBits < 30 && (size_t(1) << bucketBits) < 2 * segments.size()) ++bucketBits;
  for (size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    const int pieces = std::max(1, int(std::ceil(s.len / h)));
    mine.clear();
    for (int k = 0; k < pieces; ++k) {
      const double f0 = double(k) / pieces, f1 = double(k + 1) / pieces;
      const double x0 = s.ax + (s.bx - s.ax) * f0, x1 = s.ax + (s.bx - s.ax) * f1;
      const double z0 = s.az + (s.bz - s.az) * f0, z1 = s.az + (s.bz - s.az) * f1;
      const int64_t cx0 = cellOf(std::min(x0, x1) - tol, lo.x), cx1 = cellOf(std::max(x0, x1) + tol, lo.x);
      const int64_t cz0 = cellOf(std::min(z0, z1) - tol, lo.y), cz1 = cellOf(std::max(z0, z1) + tol, lo.y);
      for (int64_t cx = cx0; cx <= cx1; ++cx)
        for (int64_t cz = cz0; cz <= cz1; ++cz)
          mine.push_back(mix64(uint64_t(cx) << 32 | uint64_t(cz)) >> (64 - bucketBits));
    }
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    for (uint64_t c : mine) listed.emplace_back(uint32_t(c), uint32_t(i));
  }
  std::vector<size_t> bucketStart((size_t(1) << bucketBits) + 1, 0);
  for (const auto& l : listed) ++bucketStart[l.first + 1];
  std::partial_sum(bucketStart.begin(), bucketStart.end(), bucketStart.begin());
  std::vector<uint32_t> members(listed.size());
  {
    std::vector<size_t> next(bucketStart.begin(), bucketStart.end() - 1);
    for (const auto& l : listed) members[next[l.first]++] = l.second;
  }
  listed = {};

  std::vector<uint32_t> parent(segments.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> paired(segments.size(), 0);
  for (size_t bucket = 0; bucket + 1 < bucketStart.size(); ++bucket)
    for (size_t a = bucketStart[bucket]; a < bucketStart[bucket + 1]; ++a)
      for (size_t b = a + 1; b < bucketStart[bucket + 1]; ++b) {
        const uint32_t i = members[a], j = members[b];
        if (i == j || !overlapsCollinear(segments[i], segments[j], tol)) continue;
        paired[i] = paired[j] = 1;
        parent[findRoot(parent, i)] = uint32_t(findRoot(parent, j));
      }
  for (size_t i = 0; i < segments.size(); ++i) {
    if (!paired[i]) {
      ++out.unpairedEdges;
      continue;
    }
    ++out.cracks;
    out.crackSites += findRoot(parent, i) == i;
  }
  return out;
}

}  // namespace lb
