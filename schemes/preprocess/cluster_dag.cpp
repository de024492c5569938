#include "schemes/preprocess/cluster_dag.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <list>
#include <map>
#include <mutex>
#include <numeric>

#include "schemes/preprocess/tess_deviation.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

constexpr int kTileCells = 8;  // 8 x 8 cells: 128 triangles, the finest clusters
// Heights as the simplifier sees them, in sample spacings times this: a flattened surface keeps
// every triangle's normal near the vertical, so meshoptimizer's normal-flip test also refuses
// collapses that fold a triangle over in (x, z), and its quadric distance becomes about this
// times the vertical distance, the error the cut projects.
constexpr double kFlatten = 1.0 / 16.0;
// Heights as the simplifier sees them are rounded to this many steps a sample spacing: the same
// terrain at another world scale has heights rounded differently in their last bits, which the
// simplifier's quadrics (differences of nearly equal numbers) would magnify into other collapses;
// rounded, its input is bit for bit the same unless a sample lies within float rounding of a step's
// midpoint. The recorded errors use the exact heights.
constexpr double kHeightSteps = 4.0;

// Triangles as global vertex ids (z * width + x) while the DAG is built.
using Tris = std::vector<uint32_t>;

struct Builder {
  const Heightfield& hf;
  uint32_t width;
  double spacing;
  bool lockBorders;

  glm::ivec2 point(uint32_t v) const { return {int(v % width), int(v / width)}; }
  float height(uint32_t v) const { return hf.at(int(v % width), int(v / width)); }

  DagBox box(const Tris& t) const {
    DagBox b{glm::vec3(FLT_MAX), glm::vec3(-FLT_MAX)};
    for (uint32_t v : t) {
      const glm::vec3 p(float(point(v).x), height(v), float(point(v).y));
      b.lo = glm::min(b.lo, p);
      b.hi = glm::max(b.hi, p);
    }
    return b;
  }
  // Largest vertical distance of the triangles from the bilinear heightfield, in sample spacings.
  float deviation(const Tris& t) const {
    double worst = 0;
    for (size_t i = 0; i < t.size(); i += 3) {
      auto p = [&](size_t k) { return glm::dvec2(point(t[i + k])); };
      worst = std::max(worst, triangleDeviation(hf, p(0), p(1), p(2)));
    }
    return float(worst / spacing);
  }
  // Twice the signed area in (x, z): > 0 for the footprints' counter-clockwise winding.
  int64_t area2(const Tris& t, size_t i) const {
    const glm::ivec2 a = point(t[i]), b = point(t[i + 1]), c = point(t[i + 2]);
    return int64_t(b.x - a.x) * (c.y - a.y) - int64_t(b.y - a.y) * (c.x - a.x);
  }

  // meshoptimizer's flip test is in 3-D: next to a straight locked border it may leave a triangle of
  // three border points, zero area in (x, z) (a vertical sliver). Each such triangle and its
  // neighbour across its long edge become two triangles through its middle point: the border's
  // edges stay. False when a triangle stays folded or flat (the caller then asks for less).
  bool unfold(Tris& t) const {
    for (int pass = 0; pass < 64; ++pass) {
      size_t flat = t.size();
      for (size_t i = 0; i < t.size() && flat == t.size(); i += 3) {
        const int64_t a = area2(t, i);
        if (a < 0) return false;
        if (a == 0) flat = i;
      }
      if (flat == t.size()) return true;
      // The middle point m of the flat triangle, its long edge u -> v.
      size_t mid = 0;
      for (size_t k = 0; k < 3; ++k) {
        const glm::ivec2 p = point(t[flat + k]), u = point(t[flat + (k + 1) % 3]), v = point(t[flat + (k + 2) % 3]);
        if (glm::dot(glm::vec2(p - u), glm::vec2(p - v)) < 0) mid = k;
      }
      const uint32_t m = t[flat + mid], u = t[flat + (mid + 1) % 3], v = t[flat + (mid + 2) % 3];
      size_t other = t.size();
      for (size_t i = 0; i < t.size() && other == t.size(); i += 3)
        for (size_t k = 0; k < 3; ++k)
          if (t[i + k] == v && t[i + (k + 1) % 3] == u) other = i;
      if (other == t.size()) return false;  // the long edge is on the border
      uint32_t w = 0;
      for (size_t k = 0; k < 3; ++k)
        if (t[other + k] != u && t[other + k] != v) w = t[other + k];
      t[flat] = m, t[flat + 1] = u, t[flat + 2] = w;
      t[other] = m, t[other + 1] = w, t[other + 2] = v;
    }
    return false;
  }

  // Median cuts of the triangles' centroids along the longer side until every part holds at most
  // kMaxClusterTriangles triangles and kMaxClusterVertices vertices; ties broken by position in the list, so the split
  // is deterministic.
  void split(const Tris& t, std::vector<uint32_t>& order, size_t lo, size_t hi, std::vector<Tris>& out) const {
    const size_t n = hi - lo;
    std::vector<uint32_t> used;
    if (n <= size_t(kMaxClusterTriangles)) {
      for (size_t k = lo; k < hi; ++k) used.insert(used.end(), &t[size_t(order[k]) * 3], &t[size_t(order[k]) * 3 + 3]);
      std::sort(used.begin(), used.end());
      used.erase(std::unique(used.begin(), used.end()), used.end());
    }
    if (n <= size_t(kMaxClusterTriangles) && used.size() <= size_t(kMaxClusterVertices)) {
      Tris part;
      for (size_t k = lo; k < hi; ++k) part.insert(part.end(), &t[size_t(order[k]) * 3], &t[size_t(order[k]) * 3 + 3]);
      out.push_back(std::move(part));
      return;
    }
    auto sum = [&](uint32_t tri, int axis) {
      int64_t s = 0;
      for (int k = 0; k < 3; ++k)
        s += axis ? point(t[size_t(tri) * 3 + size_t(k)]).y : point(t[size_t(tri) * 3 + size_t(k)]).x;
      return s;
    };
    int64_t mn[2] = {INT64_MAX, INT64_MAX}, mx[2] = {INT64_MIN, INT64_MIN};
    for (size_t k = lo; k < hi; ++k)
      for (int a = 0; a < 2; ++a) {
        mn[a] = std::min(mn[a], sum(order[k], a));
        mx[a] = std::max(mx[a], sum(order[k], a));
      }
    const int axis = mx[1] - mn[1] > mx[0] - mn[0] ? 1 : 0;
    const size_t parts = std::max<size_t>((n + kMaxClusterTriangles - 1) / kMaxClusterTriangles, 2);
    const size_t mid = lo + n * (parts / 2) / parts;
    std::nth_element(order.begin() + long(lo), order.begin() + long(mid), order.begin() + long(hi),
                     [&](uint32_t a, uint32_t b) {
                       const int64_t sa = sum(a, axis), sb = sum(b, axis);
                       if (sa != sb) return sa < sb;
                       const int64_t oa = sum(a, 1 - axis), ob = sum(b, 1 - axis);
                       return oa != ob ? oa < ob : a < b;
                     });
    split(t, order, lo, mid, out);
    split(t, order, mid, hi, out);
  }
  std::vector<Tris> split(const Tris& t) const {
    std::vector<uint32_t> order(t.size() / 3);
    std::iota(order.begin(), order.end(), 0u);
    std::vector<Tris> out;
    split(t, order, 0, order.size(), out);
    return out;
  }

  // The group's triangles simplified to about half with its border locked; empty when it cannot
  // shrink by a tenth without folding a triangle over in (x, z).
  Tris simplify(const Tris& t) const {
    std::vector<uint32_t> verts(t);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    std::vector<uint32_t> local(t.size());
    for (size_t i = 0; i < t.size(); ++i)
      local[i] = uint32_t(std::lower_bound(verts.begin(), verts.end(), t[i]) - verts.begin());
    // Lattice units and heights in sample spacings: the same numbers at every world scale.
    std::vector<float> pos(verts.size() * 3);
    for (size_t i = 0; i < verts.size(); ++i) {
      pos[i * 3] = float(point(verts[i]).x);
      pos[i * 3 + 1] = float(std::round(double(height(verts[i])) / spacing * kHeightSteps) / kHeightSteps * kFlatten);
      pos[i * 3 + 2] = float(point(verts[i]).y);
    }
    const size_t tris = t.size() / 3;
    for (size_t eighths : {4, 5, 6, 7}) {  // half first; less where half folds a triangle
      std::vector<uint32_t> dst(local.size());
      const size_t n =
          meshopt_simplify(dst.data(), local.data(), local.size(), pos.data(), verts.size(), sizeof(float) * 3,
                           tris * eighths / 8 * 3, FLT_MAX, lockBorders ? meshopt_SimplifyLockBorder : 0u, nullptr);
      if (n / 3 * 10 > tris * 9) return {};
      Tris out(n);
      for (size_t i = 0; i < n; ++i) out[i] = verts[dst[i]];
      if (unfold(out)) return out;
    }
    return {};
  }
};

DagBox merged(const DagBox& a, const DagBox& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

}  // namespace

ClusterDag buildClusterDag(const Heightfield& hf, bool lockBorders) {
  const auto t0 = std::chrono::steady_clock::now();
  ClusterDag dag;
  const int cellsX = hf.width - 1, cellsZ = hf.height - 1;
  dag.spacing = double(hf.extent) / double(std::min(cellsX, cellsZ));
  const Builder b{hf, uint32_t(hf.width), dag.spacing, lockBorders};
  std::vector<Tris> tris;  // per cluster, global ids

  // The finest mesh in tiles of 8 x 8 cells, winding (0,0), (1,0), (1,1) as the footprints.
  for (int tz = 0; tz < cellsZ; tz += kTileCells)
    for (int tx = 0; tx < cellsX; tx += kTileCells) {
      Tris t;
      for (int z = tz; z < std::min(tz + kTileCells, cellsZ); ++z)
        for (int x = tx; x < std::min(tx + kTileCells, cellsX); ++x) {
          const uint32_t a = uint32_t(z) * b.width + uint32_t(x), c = a + b.width + 1;
          t.insert(t.end(), {a, a + 1, c, a, c, c - 1});
        }
      tris.push_back(std::move(t));
    }
  dag.clusters.resize(tris.size());
  parallelRows(
      int(tris.size()),
      [&](int r0, int r1) {
        for (int k = r0; k < r1; ++k) {
          DagCluster& c = dag.clusters[size_t(k)];
          c.tight = c.bounds = b.box(tris[size_t(k)]);
          c.error = b.deviation(tris[size_t(k)]);
        }
      },
      16);

  std::vector<int> open(tris.size());
  std::iota(open.begin(), open.end(), 0);
  for (int level = 0; open.size() > 1 && level < 64; ++level) {
    // Groups: the open clusters by their centroid's cell in a grid of about kGroupClusters clusters
    // a cell, shifted by half a cell on odd levels.
    const double g = std::sqrt(double(kGroupClusters) * double(cellsX) * double(cellsZ) / double(open.size()));
    const double shift = level % 2 ? 0.5 * g : 0.0;
    std::map<std::pair<long, long>, std::vector<int>> buckets;
    for (int k : open) {
      double cx = 0, cz = 0;
      for (uint32_t v : tris[size_t(k)]) {
        cx += b.point(v).x;
        cz += b.point(v).y;
      }
      const double n = double(tris[size_t(k)].size());
      buckets[{long(std::floor((cx / n + shift) / g)), long(std::floor((cz / n + shift) / g))}].push_back(k);
    }
    std::vector<std::vector<int>> inputs;
    for (auto& [key, members] : buckets) inputs.push_back(std::move(members));
    // Each group alone, in parallel, one at a time from a shared counter.
    std::vector<Tris> simplified(inputs.size());
    std::vector<float> measured(inputs.size(), 0.0f);
    std::atomic<size_t> next{0};
    parallelRows(
        terrainThreads(),
        [&](int, int) {
          for (size_t k; (k = next.fetch_add(1)) < inputs.size();) {
            Tris all;
            for (int c : inputs[k]) all.insert(all.end(), tris[size_t(c)].begin(), tris[size_t(c)].end());
            simplified[k] = b.simplify(all);
            if (!simplified[k].empty()) measured[k] = b.deviation(simplified[k]);
          }
        },
        1);
    std::vector<int> nextOpen;
    for (size_t k = 0; k < inputs.size(); ++k) {
      if (simplified[k].empty()) {  // stays open: regrouped on the next level
        nextOpen.insert(nextOpen.end(), inputs[k].begin(), inputs[k].end());
        continue;
      }
      DagGroup grp;
      grp.level = level;
      grp.inputs = inputs[k];
      grp.measured = grp.error = measured[k];
      grp.box = b.box(simplified[k]);
      for (int c : inputs[k]) {
        DagCluster& in = dag.clusters[size_t(c)];
        in.group = int(dag.groups.size());
        grp.error = std::max(grp.error, in.error);
        grp.box = merged(grp.box, in.bounds);
        grp.inputTriangles += uint32_t(tris[size_t(c)].size() / 3);
      }
      grp.simplifiedTriangles = uint32_t(simplified[k].size() / 3);
      for (Tris& part : b.split(simplified[k])) {
        DagCluster c;
        c.level = level + 1;
        c.madeBy = int(dag.groups.size());
        c.error = grp.error;
        c.bounds = grp.box;
        c.tight = b.box(part);
        grp.made.push_back(int(dag.clusters.size()));
        nextOpen.push_back(int(dag.clusters.size()));
        dag.clusters.push_back(c);
        tris.push_back(std::move(part));
      }
      dag.groups.push_back(std::move(grp));
    }
    if (nextOpen.size() >= open.size()) break;  // nothing shrank: the rest are roots
    std::sort(nextOpen.begin(), nextOpen.end());
    open = std::move(nextOpen);
  }

  // Each cluster's triangles as a footprint: its own lattice points, local indices.
  parallelRows(
      int(dag.clusters.size()),
      [&](int r0, int r1) {
        for (size_t k = size_t(r0); k < size_t(r1); ++k) {
          DagCluster& c = dag.clusters[k];
          std::vector<uint32_t> verts(tris[k]);
          std::sort(verts.begin(), verts.end());
          verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
          for (uint32_t v : verts) c.vertices.emplace_back(float(b.point(v).x), float(b.point(v).y));
          for (uint32_t v : tris[k])
            c.indices.push_back(uint32_t(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin()));
        }
      },
      64);
  for (const DagCluster& c : dag.clusters) {
    dag.levels = std::max(dag.levels, c.level + 1);
    dag.vertexCount += c.vertices.size();
    dag.indexCount += c.indices.size();
  }
  dag.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return dag;
}

std::shared_ptr<const ClusterDag> cachedClusterDag(const Heightfield& hf) {
  struct Entry {
    int width, height;
    float extent;
    uint64_t hash;
    std::shared_ptr<const ClusterDag> dag;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->extent == hf.extent && it->hash == hash) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().dag;
    }
  auto dag = std::make_shared<const ClusterDag>(buildClusterDag(hf));
  cache.push_front({hf.width, hf.height, hf.extent, hash, dag});
  if (cache.size() > 4) cache.pop_back();
  return dag;
}

std::vector<glm::ivec4> groupBorder(const ClusterDag& dag, const std::vector<int>& clusters) {
  std::map<std::tuple<int, int, int, int>, int> uses;
  for (int k : clusters) {
    const DagCluster& c = dag.clusters[size_t(k)];
    for (size_t i = 0; i < c.indices.size(); i += 3)
      for (int e = 0; e < 3; ++e) {
        glm::ivec2 p(c.vertices[c.indices[i + size_t(e)]]), q(c.vertices[c.indices[i + size_t(e + 1) % 3]]);
        if (std::tie(q.x, q.y) < std::tie(p.x, p.y)) std::swap(p, q);
        ++uses[{p.x, p.y, q.x, q.y}];
      }
  }
  std::vector<glm::ivec4> out;
  for (const auto& [e, n] : uses)
    if (n == 1) out.emplace_back(std::get<0>(e), std::get<1>(e), std::get<2>(e), std::get<3>(e));
  return out;
}

}  // namespace lb
