#include "schemes/preprocess/chunk_tree.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <list>
#include <mutex>
#include <unordered_map>
#include <unordered_set>

#include "schemes/preprocess/tess_deviation.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

using glm::dvec2;

uint64_t key(int x, int z) {
  return (uint64_t(uint32_t(x)) << 32) | uint32_t(z);
}

struct Cell {
  int x, z, s;
};

// One chunk's surface and skirt, and the deepest its skirt must reach.
class ChunkBuilder {
 public:
  ChunkBuilder(const Heightfield& hf, int leafCells, Chunk& c) : hf_(hf), leaf_(leafCells), c_(c) {}

  // Returns the depth below the samples this chunk's skirt bottoms need (>= 0).
  double build() {
    split(c_.x0, c_.z0, leaf_ << c_.level);
    triangulate();
    measure();
    return skirts();
  }

 private:
  double cellError(int x, int z, int s) const {
    const dvec2 a(x, z), b(x + s, z), c(x + s, z + s), d(x, z + s);
    return std::max(triangleDeviation(hf_, a, b, c), triangleDeviation(hf_, a, c, d));
  }
  void split(int x, int z, int s) {
    if (x >= c_.x1 || z >= c_.z1) return;  // past the terrain's last sample
    const bool partial = x + s > c_.x1 || z + s > c_.z1;
    if (partial || (s > 1 && cellError(x, z, s) > double(c_.target))) {
      const int h = s / 2;
      for (int q = 0; q < 4; ++q) split(x + (q & 1) * h, z + (q >> 1) * h, h);
      return;
    }
    leaves_.push_back({x, z, s});
    for (int q = 0; q < 4; ++q) corners_.insert(key(x + (q & 1) * s, z + (q >> 1) * s));
  }
  uint32_t vertex(int x, int z) {
    auto [it, added] = index_.try_emplace(key(x, z), uint32_t(c_.mesh.vertices.size()));
    if (added) c_.mesh.vertices.emplace_back(float(x), float(z));
    return it->second;
  }
  uint32_t bottom(int x, int z) {
    auto [it, added] = bottomIndex_.try_emplace(key(x, z), uint32_t(c_.mesh.vertices.size()));
    if (added) c_.mesh.vertices.emplace_back(skirtBottomX(x), float(z));
    return it->second;
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) { c_.mesh.indices.insert(c_.mesh.indices.end(), {a, b, c}); }

  // Counter-clockwise in (x, z) like the instanced footprints: (0,0), (1,0), (1,1).
  void triangulate() {
    std::vector<std::pair<int, int>> loop;
    for (const Cell& l : leaves_) {
      loop.clear();
      auto add = [&](int x, int z, bool corner) {
        if (corner || corners_.count(key(x, z))) loop.emplace_back(x, z);
      };
      for (int x = l.x; x < l.x + l.s; ++x) add(x, l.z, x == l.x);
      for (int z = l.z; z < l.z + l.s; ++z) add(l.x + l.s, z, z == l.z);
      for (int x = l.x + l.s; x > l.x; --x) add(x, l.z + l.s, x == l.x + l.s);
      for (int z = l.z + l.s; z > l.z; --z) add(l.x, z, z == l.z + l.s);
      if (loop.size() == 4) {
        const uint32_t a = vertex(l.x, l.z), b = vertex(l.x + l.s, l.z), c = vertex(l.x + l.s, l.z + l.s),
                       d = vertex(l.x, l.z + l.s);
        triangle(a, b, c);
        triangle(a, c, d);
        continue;
      }
      // Smaller neighbours' corners on a side: a fan from the centre (s >= 2 here, as a single
      // cell's sides hold no lattice point between its corners).
      const uint32_t m = vertex(l.x + l.s / 2, l.z + l.s / 2);
      for (size_t i = 0; i < loop.size(); ++i) {
        const auto& p = loop[i];
        const auto& q = loop[(i + 1) % loop.size()];
        triangle(m, vertex(p.first, p.second), vertex(q.first, q.second));
      }
    }
    c_.surfaceTriangles = uint32_t(c_.mesh.indices.size() / 3);
  }
  void measure() {
    double worst = 0;
    const auto& v = c_.mesh.vertices;
    for (size_t t = 0; t < c_.mesh.indices.size(); t += 3) {
      auto p = [&](size_t k) { return dvec2(v[c_.mesh.indices[t + k]]); };
      worst = std::max(worst, triangleDeviation(hf_, p(0), p(1), p(2)));
    }
    c_.measured = float(worst);
    c_.hmin = c_.hmax = hf_.at(c_.x0, c_.z0);
    for (int z = c_.z0; z <= c_.z1; ++z)
      for (int x = c_.x0; x <= c_.x1; ++x) {
        c_.hmin = std::min(c_.hmin, hf_.at(x, z));
        c_.hmax = std::max(c_.hmax, hf_.at(x, z));
      }
  }

  // One wall per side off the terrain border; the side runs from (x, z) along (dx, dz) for n cells.
  double skirts() {
    double depth = 0;
    if (c_.z0 > 0) depth = std::max(depth, skirt(c_.x0, c_.z0, 1, 0, c_.x1 - c_.x0, true));
    if (c_.x1 < hf_.width - 1) depth = std::max(depth, skirt(c_.x1, c_.z0, 0, 1, c_.z1 - c_.z0, true));
    if (c_.z1 < hf_.height - 1) depth = std::max(depth, skirt(c_.x0, c_.z1, 1, 0, c_.x1 - c_.x0, false));
    if (c_.x0 > 0) depth = std::max(depth, skirt(c_.x0, c_.z0, 0, 1, c_.z1 - c_.z0, false));
    c_.skirtTriangles = uint32_t(c_.mesh.indices.size() / 3) - c_.surfaceTriangles;
    return depth;
  }
  // `outward`: the chunk lies to the left of the side's direction (south and east sides), which
  // decides the winding that keeps the wall's front outside the chunk.
  double skirt(int x, int z, int dx, int dz, int n, bool outward) {
    std::vector<int> top, bot;  // positions along the side, 0..n
    for (int u = 0; u <= n; ++u) {
      if (index_.count(key(x + u * dx, z + u * dz))) top.push_back(u);
      const int along = (dx ? x : z) + u;
      if (u == 0 || u == n || along % leaf_ == 0) bot.push_back(u);
    }
    auto h = [&](int u) { return double(hf_.at(x + u * dx, z + u * dz)); };
    // The surface along the side: the polyline through its top vertices, at every lattice point.
    std::vector<double> surface(size_t(n) + 1);
    for (size_t k = 0; k + 1 < top.size(); ++k)
      for (int u = top[k]; u <= top[k + 1]; ++u)
        surface[size_t(u)] = h(top[k]) + (h(top[k + 1]) - h(top[k])) * double(u - top[k]) / double(top[k + 1] - top[k]);
    // The wall: a strip between the top vertices and the bottom points, each triangle one step of
    // either chain. Every rung (a top vertex to a bottom point) and the bottom line must stay under
    // the surface, or the wall shows above the ground; both are linear between lattice points, so
    // checking lattice points is exact. The depth that achieves it: rung(u) = y_T + (t_B - D - y_T) w
    // <= surface(u) with w the rung's fraction towards its bottom end.
    std::vector<std::pair<size_t, size_t>> rungs = {{0, 0}};
    while (rungs.back().first + 1 < top.size() || rungs.back().second + 1 < bot.size()) {
      const auto [i, j] = rungs.back();
      const bool advanceTop = j + 1 == bot.size() || (i + 1 < top.size() && top[i + 1] <= bot[j + 1]);
      rungs.emplace_back(advanceTop ? i + 1 : i, advanceTop ? j : j + 1);
    }
    double depth = 0;
    for (size_t b = 0; b + 1 < bot.size(); ++b)
      for (int u = bot[b]; u <= bot[b + 1]; ++u) {
        const double l = h(bot[b]) + (h(bot[b + 1]) - h(bot[b])) * double(u - bot[b]) / double(bot[b + 1] - bot[b]);
        depth = std::max(depth, l - surface[size_t(u)]);
      }
    for (const auto& [i, j] : rungs) {
      const int uT = top[i], uB = bot[j];
      for (int u = std::min(uT, uB) + 1; u < std::max(uT, uB); ++u) {
        const double w = double(u - uT) / double(uB - uT);
        depth = std::max(depth, (h(uT) + (h(uB) - h(uT)) * w - surface[size_t(u)]) / w);
      }
    }
    auto T = [&](size_t k) { return vertex(x + top[k] * dx, z + top[k] * dz); };
    auto B = [&](size_t k) { return bottom(x + bot[k] * dx, z + bot[k] * dz); };
    auto wall = [&](uint32_t a, uint32_t b, uint32_t c) { outward ? triangle(a, b, c) : triangle(a, c, b); };
    for (size_t r = 1; r < rungs.size(); ++r) {
      const auto [i, j] = rungs[r - 1];
      if (rungs[r].first != i)
        wall(T(i), T(i + 1), B(j));
      else
        wall(T(i), B(j + 1), B(j));
    }
    return depth;
  }

  const Heightfield& hf_;
  int leaf_;
  Chunk& c_;
  std::vector<Cell> leaves_;
  std::unordered_set<uint64_t> corners_;
  std::unordered_map<uint64_t, uint32_t> index_, bottomIndex_;
};

}  // namespace

ChunkTree buildChunkTree(const Heightfield& hf, int leafCells, double leafErrorCells) {
  const auto t0 = std::chrono::steady_clock::now();
  ChunkTree tree;
  tree.leafCells = leafCells;
  const int cellsX = hf.width - 1, cellsZ = hf.height - 1;
  const double spacing = double(hf.extent) / double(std::min(cellsX, cellsZ));
  tree.leafError = leafErrorCells * spacing;
  tree.levels = 1;
  while ((leafCells << (tree.levels - 1)) < std::max(cellsX, cellsZ)) ++tree.levels;
  // Levels from the leaves up, each level's chunks in rows; children of the level below by index.
  std::vector<int> first(size_t(tree.levels)), cols(size_t(tree.levels)), rows(size_t(tree.levels));
  for (int l = 0; l < tree.levels; ++l) {
    const int s = leafCells << l;
    cols[size_t(l)] = (cellsX + s - 1) / s;
    rows[size_t(l)] = (cellsZ + s - 1) / s;
    first[size_t(l)] = int(tree.chunks.size());
    for (int j = 0; j < rows[size_t(l)]; ++j)
      for (int i = 0; i < cols[size_t(l)]; ++i) {
        Chunk c;
        c.level = l;
        c.x0 = i * s;
        c.z0 = j * s;
        c.x1 = std::min(c.x0 + s, cellsX);
        c.z1 = std::min(c.z0 + s, cellsZ);
        c.target = float(std::ldexp(tree.leafError, l));
        if (l > 0)
          for (int q = 0; q < 4; ++q) {
            const int ci = 2 * i + (q & 1), cj = 2 * j + (q >> 1);
            if (ci < cols[size_t(l - 1)] && cj < rows[size_t(l - 1)])
              c.children[q] = first[size_t(l - 1)] + cj * cols[size_t(l - 1)] + ci;
          }
        tree.chunks.push_back(std::move(c));
      }
  }
  // Chunks from the root down (a coarse chunk costs most), each thread taking the next one: bands
  // of the list would leave one thread all the coarse levels. Chunks are independent, so the tree
  // does not depend on who built what.
  std::vector<double> depth(tree.chunks.size(), 0.0);
  std::atomic<size_t> next{0};
  parallelRows(
      terrainThreads(),
      [&](int, int) {
        for (size_t k; (k = next.fetch_add(1)) < tree.chunks.size();) {
          const size_t c = tree.chunks.size() - 1 - k;
          depth[c] = ChunkBuilder(hf, leafCells, tree.chunks[c]).build();
        }
      },
      1);
  for (Chunk& c : tree.chunks) {  // children precede parents
    c.error = c.measured;
    for (int ch : c.children)
      if (ch >= 0) c.error = std::max(c.error, tree.chunks[size_t(ch)].error);
    tree.vertexCount += c.mesh.vertices.size();
    tree.indexCount += c.mesh.indices.size();
  }
  tree.skirtDepth = float(*std::max_element(depth.begin(), depth.end()));
  tree.root = int(tree.chunks.size()) - 1;
  tree.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return tree;
}

std::shared_ptr<const ChunkTree> cachedChunkTree(const Heightfield& hf, int leafCells, double leafErrorCells) {
  struct Entry {
    int width, height, leafCells;
    float extent;
    double leafErrorCells;
    uint64_t hash;
    std::shared_ptr<const ChunkTree> tree;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->extent == hf.extent && it->hash == hash &&
        it->leafCells == leafCells && it->leafErrorCells == leafErrorCells) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().tree;
    }
  auto tree = std::make_shared<const ChunkTree>(buildChunkTree(hf, leafCells, leafErrorCells));
  cache.push_front({hf.width, hf.height, leafCells, hf.extent, leafErrorCells, hash, tree});
  if (cache.size() > 4) cache.pop_back();
  return tree;
}

}  // namespace lb
