#pragma once
// Load-time part of `clusters` (schemes/clusters.cpp): a Nanite-style DAG of clusters of at most
// kMaxClusterTriangles triangles, built offline from the finest terrain mesh.
//
// Lattice: one cell per heightfield sample spacing, terrain-local integer coordinates, as the
// instanced path's footprints (render/instanced.h); every vertex of every level is a heightfield
// sample (edge collapse keeps original vertices), so heights stay exact.
//
// Build, level by level from the finest mesh (two triangles a cell, diagonal (0,0)-(1,1)), whose
// clusters are tiles of 8 x 8 cells:
//   1. group the level's open clusters, about kGroupClusters a group, by their centroid's cell in a
//      square grid sized for that count, the grid shifted by half a cell on odd levels so that a
//      group's border runs through the groups of the level below rather than along their borders;
//   2. simplify each group's triangles alone to half (meshoptimizer's meshopt_simplify with
//      meshopt_SimplifyLockBorder: a vertex on an edge that only one triangle of the group uses
//      stays, so the group's outer border is kept bit for bit and its neighbours, at any level,
//      still meet it); positions (x, height / spacing, z) in lattice units, so the input is the
//      same at every world scale;
//   3. split the simplified group into clusters of at most kMaxClusterTriangles triangles and
//      kMaxClusterVertices vertices (median cuts of the triangles' centroids along the longer
//      side), which are the next level's clusters.
// A group that simplification cannot shrink by a tenth stays open and is regrouped on the next
// level; the build stops when no group shrinks. Clusters never simplified are roots.
//
// Errors, in sample spacings (scale-free): a group's error is the exact largest vertical distance of
// its simplified triangles from the bilinear heightfield (schemes/preprocess/tess_deviation.h),
// raised to every input cluster's own error, so errors never fall up the DAG. A level-0 cluster's
// own error is its own triangles' distance (the cell diagonals against the bilinear surface).
// Bounds: a group's box holds its input clusters' own boxes, so a group's projected error is never
// smaller than that of a group below it (the selection's cut is then consistent).
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "shaders/clusters_params.h"

namespace lb {

struct Heightfield;

constexpr int kMaxClusterTriangles = LB_CLUSTERS_MAX_TRIANGLES;
constexpr int kMaxClusterVertices = LB_CLUSTERS_MAX_VERTICES;
constexpr int kGroupClusters = 4;

// Lattice x, z and world heights.
struct DagBox {
  glm::vec3 lo{0.0f}, hi{0.0f};
};

struct DagCluster {
  int level = 0;                    // simplifications its triangles went through
  std::vector<glm::vec2> vertices;  // lattice points
  std::vector<uint32_t> indices;    // triangle list into vertices
  int madeBy = -1;                  // the group whose simplification made it (-1: the finest mesh)
  int group = -1;                   // the group that simplifies it (-1: a root)
  float error = 0;                  // own error, sample spacings: madeBy's error, or its own (level 0)
  DagBox bounds;                    // own bounds: madeBy's box, or its own (level 0)
  DagBox tight;                     // its own vertices' box (culling)
  uint32_t triangles() const { return uint32_t(indices.size() / 3); }
};

struct DagGroup {
  int level = 0;
  std::vector<int> inputs;  // its clusters
  std::vector<int> made;    // the clusters its simplification made
  float measured = 0;       // its simplified triangles' largest distance, sample spacings
  float error = 0;          // max(measured, inputs' own errors)
  DagBox box;               // holds every input's own bounds
  uint32_t inputTriangles = 0, simplifiedTriangles = 0;
};

struct ClusterDag {
  std::vector<DagCluster> clusters;
  std::vector<DagGroup> groups;
  int levels = 0;      // cluster levels 0 .. levels - 1
  double spacing = 0;  // world units per sample spacing (errors' unit)
  double buildSeconds = 0;
  uint64_t vertexCount = 0, indexCount = 0;
  uint64_t meshBytes() const { return vertexCount * 8 + indexCount * 4; }  // as the instanced path uploads them
};

// Contract: heightfield at least 2 x 2. Groups of one level are simplified in parallel; the result
// does not depend on the thread count. lockBorders = false is the tests' planted defect: group
// borders then simplify too, and cuts of mixed levels crack.
ClusterDag buildClusterDag(const Heightfield& hf, bool lockBorders = true);

// The same, kept for the last few terrains (heights, size, extent). Safe on any thread.
std::shared_ptr<const ClusterDag> cachedClusterDag(const Heightfield& hf);

// A group's outer border: its triangles' edges that only one of its triangles uses, as sorted
// lattice point pairs (x0, z0, x1, z1), sorted. The tests compare a group's and its simplification's.
std::vector<glm::ivec4> groupBorder(const ClusterDag& dag, const std::vector<int>& clusters);

}  // namespace lb
