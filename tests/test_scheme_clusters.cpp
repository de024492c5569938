// clusters (schemes/clusters.cpp): its offline DAG and its cut. The DAG: at most 128 triangles and
// 255 vertices a cluster, on the lattice, never folded over; errors exact and never falling up the
// DAG, boxes nested; every group's outer border bit-identical to its simplification's; the same DAG
// at any world scale and on any number of threads. Cuts by the scheme's rule, assembled on the CPU
// as shaders/clusters_vertex.glsl places them, are closed and cover the terrain once
// (metrics/mesh_cracks.h), and two planted defects break them: unlocked group borders crack, a
// non-monotone error overlaps two levels. clusters-ms's table holds every cluster as its footprint.
// The GPU side: tests/test_scheme_clusters_sweep.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "metrics/mesh_cracks.h"
#include "render/scheme.h"
#include "schemes/preprocess/cluster_dag.h"
#include "schemes/preprocess/tess_deviation.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "threads_env.h"

using namespace lb;

namespace {

Heightfield procedural(int size, float heightScale = 150.0f) {
  TerrainSpec s;
  s.size = size;
  s.seed = 3;
  s.extent = 1000.0f;
  s.heightScale = heightScale;
  return makeProcedural(s);
}

bool contains(const DagBox& outer, const DagBox& inner) {
  return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

double boxDistance(const DagBox& b, glm::dvec3 p) {
  const glm::dvec3 d = glm::max(glm::max(glm::dvec3(b.lo) - p, p - glm::dvec3(b.hi)), glm::dvec3(0.0));
  return glm::length(d);
}

// The scheme's cut in lattice units (heights in sample spacings times `spacing`): groups coarse
// enough when error / distance <= t, seen from `eye`.
std::vector<int> cut(const ClusterDag& dag, glm::dvec3 eye, double t) {
  std::vector<char> coarse(dag.groups.size());
  for (size_t g = 0; g < dag.groups.size(); ++g) {
    const double d = boxDistance(dag.groups[g].box, eye);
    coarse[g] = dag.groups[g].error <= 0 || (d > 0 && dag.groups[g].error / d <= t);
  }
  std::vector<int> out;
  for (size_t k = 0; k < dag.clusters.size(); ++k) {
    const DagCluster& c = dag.clusters[k];
    if ((c.madeBy < 0 || coarse[size_t(c.madeBy)]) && (c.group < 0 || !coarse[size_t(c.group)])) out.push_back(int(k));
  }
  return out;
}

// The cut's triangles in world space, each vertex as shaders/clusters.vert computes it (terrain at
// the origin, one lattice cell a sample spacing, heights at samples).
std::vector<glm::vec3> assemble(const Heightfield& hf, const ClusterDag& dag, const std::vector<int>& cut) {
  const glm::vec2 cell(hf.extent / float(hf.width - 1), hf.extent / float(hf.height - 1));
  std::vector<glm::vec3> out;
  for (int k : cut)
    for (uint32_t i : dag.clusters[size_t(k)].indices) {
      const glm::vec2 g = dag.clusters[size_t(k)].vertices[i];
      out.emplace_back(g.x * cell.x, hf.at(int(g.x), int(g.y)), g.y * cell.y);
    }
  return out;
}

// Twice the cut's area in lattice cells, exactly (integer vertices).
int64_t area2(const ClusterDag& dag, const std::vector<int>& cut) {
  int64_t sum = 0;
  for (int k : cut) {
    const DagCluster& c = dag.clusters[size_t(k)];
    for (size_t i = 0; i < c.indices.size(); i += 3) {
      const glm::ivec2 a(c.vertices[c.indices[i]]), b(c.vertices[c.indices[i + 1]]), d(c.vertices[c.indices[i + 2]]);
      sum += int64_t(b.x - a.x) * (d.y - a.y) - int64_t(b.y - a.y) * (d.x - a.x);
    }
  }
  return sum;
}

MeshCrackResult cracksOf(const Heightfield& hf, const std::vector<glm::vec3>& tris) {
  return meshCracks(tris, {glm::vec2(0.0f), glm::vec2(hf.extent)});
}

// Eyes over the terrain in lattice units, heights in sample spacings: corners, centre, low and high.
std::vector<glm::dvec3> eyes(const Heightfield& hf) {
  const double w = hf.width - 1, h = hf.height - 1;
  return {{0, 20, 0}, {w / 2, 5, h / 2}, {w, 60, h / 3}, {w / 4, 200, h}};
}

}  // namespace

TEST(ClusterDag, ClustersBoundedErrorsExactAndMonotoneBordersKept) {
  for (int size : {129, 200}) {  // a power of two plus one, and a terrain the tiles clip
    SCOPED_TRACE(size);
    const Heightfield hf = procedural(size);
    const ClusterDag dag = buildClusterDag(hf);
    const double spacing = dag.spacing;
    ASSERT_GE(dag.levels, 4);
    size_t finest = 0, roots = 0, mostVertices = 0;
    for (const DagCluster& c : dag.clusters) {
      mostVertices = std::max(mostVertices, c.vertices.size());
      EXPECT_LE(c.vertices.size(), size_t(kMaxClusterVertices));
      EXPECT_GT(c.triangles(), 0u);
      EXPECT_LE(c.triangles(), uint32_t(kMaxClusterTriangles));
      EXPECT_TRUE(contains(c.bounds, c.tight));
      double worst = 0;
      for (size_t i = 0; i < c.indices.size(); i += 3) {
        glm::dvec2 p[3];
        for (int k = 0; k < 3; ++k) p[k] = glm::dvec2(c.vertices[c.indices[i + size_t(k)]]);
        for (const glm::dvec2& q : p) EXPECT_EQ(q, glm::floor(q)) << "off the lattice";
        EXPECT_GT((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x), 0.0)
            << "a triangle folded over (or degenerate) in x, z";
        worst = std::max(worst, triangleDeviation(hf, p[0], p[1], p[2]));
      }
      if (c.madeBy < 0) {
        ++finest;
        EXPECT_EQ(c.error, float(worst / spacing)) << "a finest cluster's own error is its triangles'";
      } else {
        const DagGroup& g = dag.groups[size_t(c.madeBy)];
        EXPECT_EQ(c.error, g.error);
        EXPECT_LE(float(worst / spacing), g.measured);
      }
      roots += c.group < 0;
    }
    for (const DagGroup& g : dag.groups) {
      ASSERT_FALSE(g.made.empty());
      EXPECT_LT(g.simplifiedTriangles, g.inputTriangles);
      EXPECT_GE(g.error, g.measured);
      for (int in : g.inputs) {
        EXPECT_GE(g.error, dag.clusters[size_t(in)].error) << "an error falls up the DAG";
        EXPECT_TRUE(contains(g.box, dag.clusters[size_t(in)].bounds)) << "a box shrinks up the DAG";
      }
      EXPECT_EQ(groupBorder(dag, g.inputs), groupBorder(dag, g.made)) << "a group's border moved";
      double worst = 0;  // the simplification's exact error, recomputed
      for (int m : g.made) {
        const DagCluster& c = dag.clusters[size_t(m)];
        for (size_t i = 0; i < c.indices.size(); i += 3)
          worst = std::max(worst, triangleDeviation(hf, glm::dvec2(c.vertices[c.indices[i]]),
                                                    glm::dvec2(c.vertices[c.indices[i + 1]]),
                                                    glm::dvec2(c.vertices[c.indices[i + 2]])));
      }
      EXPECT_EQ(g.measured, float(worst / spacing));
    }
    // The roots are a few times fewer triangles than the finest mesh (the terrain's outline stays
    // locked, at full resolution, in every group that holds it).
    uint64_t rootTriangles = 0;
    for (const DagCluster& c : dag.clusters) rootTriangles += c.group < 0 ? c.triangles() : 0;
    const uint64_t full = uint64_t(hf.width - 1) * uint64_t(hf.height - 1) * 2;
    std::printf(
        "[ClusterDag] %dx%d: %zu finest clusters, %zu clusters, %zu groups, %d levels, %zu roots of %llu "
        "triangles (finest %llu), %.3f s, at most %zu vertices a cluster\n",
        hf.width, hf.height, finest, dag.clusters.size(), dag.groups.size(), dag.levels, roots,
        (unsigned long long)rootTriangles, (unsigned long long)full, dag.buildSeconds, mostVertices);
    EXPECT_LT(rootTriangles * 4, full);
  }
}

TEST(ClusterDag, EveryCutIsClosedAndPlantedDefectsBreakIt) {
  const Heightfield hf = procedural(129);
  const ClusterDag dag = buildClusterDag(hf);
  const int64_t terrain2 = int64_t(hf.width - 1) * (hf.height - 1) * 2;
  int mixed = 0;
  for (const glm::dvec3& eye : eyes(hf))
    for (double t : {0.002, 0.01, 0.05}) {
      const std::vector<int> c = cut(dag, eye, t);
      int lo = 99, hi = -1;
      for (int k : c) {
        lo = std::min(lo, dag.clusters[size_t(k)].level);
        hi = std::max(hi, dag.clusters[size_t(k)].level);
      }
      mixed += hi - lo >= 2;
      EXPECT_EQ(area2(dag, c), terrain2) << "the cut covers the terrain once";
      const MeshCrackResult r = cracksOf(hf, assemble(hf, dag, c));
      EXPECT_EQ(r.crackSites, 0);
      EXPECT_EQ(r.unpairedEdges, 0) << "every interior edge pairs";
    }
  EXPECT_GE(mixed, 4) << "cuts whose levels differ by two or more";

  // Unlocked group borders: the same cuts crack.
  const ClusterDag loose = buildClusterDag(hf, false);
  long sites = 0;
  for (const glm::dvec3& eye : eyes(hf))
    for (double t : {0.002, 0.01, 0.05}) sites += cracksOf(hf, assemble(hf, loose, cut(loose, eye, t))).crackSites;
  EXPECT_GT(sites, 0) << "unlocked borders";

  // A non-monotone error: a group below another made worse than it. Where the upper group is
  // coarse enough and the lower one is not, both draw: the cut covers that place twice.
  ClusterDag bad = dag;
  int lower = -1, upper = -1;
  for (size_t g = 0; g < bad.groups.size() && lower < 0; ++g)
    for (int in : bad.groups[g].inputs)
      if (bad.clusters[size_t(in)].madeBy >= 0) {
        lower = bad.clusters[size_t(in)].madeBy;
        upper = int(g);
        break;
      }
  ASSERT_GE(lower, 0);
  bad.groups[size_t(lower)].error = bad.groups[size_t(upper)].error * 4 + 1;
  for (int m : bad.groups[size_t(lower)].made) bad.clusters[size_t(m)].error = bad.groups[size_t(lower)].error;
  // Seen from far above, with the bound between the two errors.
  const glm::dvec3 far(64, 1e4, 64);
  const double t = bad.groups[size_t(upper)].error * 2 / boxDistance(bad.groups[size_t(upper)].box, far);
  const std::vector<int> c = cut(bad, far, t);
  EXPECT_GT(area2(bad, c), terrain2) << "a non-monotone error";
  EXPECT_EQ(area2(dag, cut(dag, far, t)), terrain2);
}

// The same terrain at x0.01 and x100 (extent and heights) gives the same DAG: the same triangles in
// every cluster and group, errors (sample spacings) equal up to float rounding.
TEST(ClusterDag, SameDagAtEveryWorldScale) {
  auto build = [](double scale) {
    TerrainSpec s;
    s.size = 129;
    s.seed = 7;
    s.extent = float(1000 * scale);
    s.heightScale = float(120 * scale);
    return buildClusterDag(makeProcedural(s));
  };
  const ClusterDag base = build(1);
  for (double scale : {0.01, 100.0}) {
    SCOPED_TRACE(scale);
    const ClusterDag dag = build(scale);
    ASSERT_EQ(dag.clusters.size(), base.clusters.size());
    ASSERT_EQ(dag.groups.size(), base.groups.size());
    for (size_t k = 0; k < dag.clusters.size(); ++k) {
      EXPECT_EQ(dag.clusters[k].vertices, base.clusters[k].vertices);
      EXPECT_EQ(dag.clusters[k].indices, base.clusters[k].indices);
      EXPECT_EQ(dag.clusters[k].group, base.clusters[k].group);
      EXPECT_NEAR(dag.clusters[k].error, base.clusters[k].error, 1e-5 * (base.clusters[k].error + 1e-3));
    }
  }
}

// clusters-ms's table (shaders/clusters_params.h), decoded as shaders/clusters_ms.mesh reads it,
// holds every cluster's footprint: the same lattice points and triangles the instanced route draws.
TEST(ClustersMs, TableHoldsEveryClusterAsItsFootprint) {
  const Heightfield hf = procedural(129);
  const Scheme& ms = *findScheme("clusters-ms");
  ASSERT_EQ(ms.info().path, DrawPath::Mesh);
  const std::unique_ptr<InstancedLod> lod = ms.instancedLod(hf, resolveParams(ms.info(), {}));
  const std::vector<Footprint>& fp = lod->footprints();
  const std::vector<uint32_t> words = lod->meshTable();
  ASSERT_EQ(words.at(0), fp.size());
  for (size_t k = 0; k < fp.size(); ++k) {
    const uint32_t v0 = words.at(1 + 3 * k), t0 = words.at(2 + 3 * k), counts = words.at(3 + 3 * k);
    ASSERT_EQ(counts & 0xffffu, fp[k].vertices.size());
    ASSERT_EQ(counts >> 16, fp[k].indices.size() / 3);
    ASSERT_LE(fp[k].vertices.size(), size_t(LB_CLUSTERS_MAX_VERTICES));
    for (size_t i = 0; i < fp[k].vertices.size(); ++i) {
      const uint32_t w = words.at(v0 + i);
      EXPECT_EQ(glm::vec2(float(w & 0xffffu), float(w >> 16)), fp[k].vertices[i]);
    }
    for (size_t t = 0; t < fp[k].indices.size() / 3; ++t) {
      const uint32_t w = words.at(t0 + t);
      for (uint32_t c = 0; c < 3; ++c) EXPECT_EQ((w >> (8 * c)) & 0xffu, fp[k].indices[t * 3 + c]);
    }
  }
}

// Groups are simplified and clusters finished on any number of threads: the DAG is the same.
TEST(ClusterDag, SameDagOnAnyThreadCount) {
  const Heightfield hf = procedural(200);
  ThreadsEnv threads(1);
  const ClusterDag one = buildClusterDag(hf);
  threads.set(3);
  const ClusterDag three = buildClusterDag(hf);
  ASSERT_EQ(one.clusters.size(), three.clusters.size());
  for (size_t k = 0; k < one.clusters.size(); ++k) {
    EXPECT_EQ(one.clusters[k].vertices, three.clusters[k].vertices);
    EXPECT_EQ(one.clusters[k].indices, three.clusters[k].indices);
    EXPECT_EQ(one.clusters[k].error, three.clusters[k].error);
  }
}
