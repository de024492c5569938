#version 450
#extension GL_GOOGLE_include_directive : require
// clusters (schemes/clusters.cpp): a vertex of a cluster of the offline DAG, at its heightfield
// sample (schemes/preprocess/cluster_dag.h), placed by shaders/clusters_vertex.glsl.
#define LB_INSTANCED_VERTEX
#include "terrain_vertex.glsl"
#include "clusters_params.h"
#include "clusters_vertex.glsl"

void main() {
  float level;
  vec3 world = clusterVertex(inLattice, instanceRecord().a.y, level);
  emitTerrainVertex(world, level);
}
