// cbt-ms (schemes/cbt_ms.cpp): how a leaf's 4^s micro-triangles (shaders/cbt_leaf.glsl) fill mesh
// workgroups, for the task shader that counts them and the mesh shader that emits them. A leaf of
// side n = 2^s has (n + 1)(n + 2) / 2 vertices and n^2 triangles. Up to s = 4 (153 and 256) a
// workgroup holds whole leaves, as many as fit 256 vertices and 256 triangles and at most a task
// workgroup's LB_CBT_GROUP (s = 0: 64, 1: 42, 2: 16, 3: 4, 4: 1); at s = 5 a leaf is four
// workgroups, its corner triangles and its middle one (turned by half a turn, so it winds the same
// way) of side 16 each.
#include "cbt_params.h"

int cbtSubd() { return int(schemeParam(LB_CBT_SUBD)); }
int cbtMeshletSide() { return min(1 << cbtSubd(), 16); }
int cbtMeshletsPerLeaf() {
  int k = (1 << cbtSubd()) / cbtMeshletSide();
  return k * k;
}
int cbtTriangleVertices(int n) { return (n + 1) * (n + 2) / 2; }
int cbtLeavesPerMeshlet() {
  int n = cbtMeshletSide();
  return min(min(256 / cbtTriangleVertices(n), 256 / (n * n)), LB_CBT_GROUP);
}
