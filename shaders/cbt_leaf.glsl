// cbt (schemes/cbt.cpp): a point of one leaf's triangle cut into 4^s micro-triangles, for the
// instanced leaf mesh (shaders/cbt.vert) and the mesh path (shaders/cbt_ms.mesh) alike. (u, v),
// 0 <= u + v <= 2^s, walk from the right-angle corner b towards a and c; every step is a whole
// lattice unit, so corners and edges two leaves share are bit-identical.
#include "cbt_params.h"

// The world point; `level` gets the heat map's equivalent level.
vec3 cbtLeafPoint(InstanceRecord r, vec2 uv, out float level) {
  vec2 a = r.a.xy, b = r.a.zw, c = r.b.xy;
  float n = exp2(schemeParam(LB_CBT_SUBD));
  precise vec2 lattice = b + uv.x * ((a - b) / n) + uv.y * ((c - b) / n);
  precise vec2 local = lattice * (frame.terrain.x / r.b.w);
  precise vec2 xz = frame.origin.xy + local;
  float cell = length(a - b) / n * (frame.terrain.x / r.b.w);
  level = equivalentLevel(cell);
  return vec3(xz.x, terrainHeight(xz), xz.y);
}
