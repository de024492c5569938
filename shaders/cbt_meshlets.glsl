// cbt-ms (schemes/cbt_ms.cpp): how a leaf's 4^s micro-triangles (shaders/cbt_leaf.glsl) fill mesh
// workgroups, for the task shader that counts them and the mesh shader that emits them. A leaf of
// side n = 2^s has (n + 1)(n + 2) / 2 vertices and n^2 triangles. A workgroup emits at most
// LB_CBT_MS_OUTPUTS vertices and as many triangles (the outputs it declares, which set how many
// workgroups a multiprocessor holds). Leaves that fit go whole, as many to a workgroup as fit and
// at most a task workgroup's LB_CBT_GROUP (at 256: s = 0: 64, 1: 42, 2: 16, 3: 4, 4: 1); a larger
// leaf is cut into k^2 triangles of side m = n / k, the largest power of two that fits: k (k + 1) / 2
// upright ones and k (k - 1) / 2 turned by half a turn (so they wind the same way), one a workgroup.
#include "cbt_params.h"

#ifndef LB_CBT_MS_OUTPUTS
#define LB_CBT_MS_OUTPUTS 256
#endif

int cbtSubd() { return int(schemeParam(LB_CBT_SUBD)); }
int cbtTriangleVertices(int n) { return (n + 1) * (n + 2) / 2; }
int cbtMeshletSide() {
  int m = 1 << cbtSubd();
  while (m > 1 && (m * m > LB_CBT_MS_OUTPUTS || cbtTriangleVertices(m) > LB_CBT_MS_OUTPUTS)) m /= 2;
  return m;
}
int cbtMeshletsPerLeaf() {
  int k = (1 << cbtSubd()) / cbtMeshletSide();
  return k * k;
}
int cbtLeavesPerMeshlet() {
  int n = cbtMeshletSide();
  return min(min(LB_CBT_MS_OUTPUTS / cbtTriangleVertices(n), LB_CBT_MS_OUTPUTS / (n * n)), LB_CBT_GROUP);
}
