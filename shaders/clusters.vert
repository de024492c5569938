#version 450
#extension GL_GOOGLE_include_directive : require
// clusters (schemes/clusters.cpp): a vertex of a cluster of the offline DAG, at its heightfield
// sample (schemes/preprocess/cluster_dag.h). Clusters meeting at a locked group border hold the
// same lattice points, so their shared vertices are computed from the same integers bit for bit.
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "clusters_params.h"

void main() {
  InstanceRecord r = instanceRecord();
  vec2 xz = latticeToWorld(inLattice, 1.0);
  precise float h = terrainHeight(xz);
  vec2 cell = latticeCell(1.0);
  // A level halves the triangles: edges about sqrt(2) longer a level.
  emitTerrainVertex(vec3(xz.x, h, xz.y), equivalentLevel(max(cell.x, cell.y) * exp2(0.5 * r.a.y)));
}
