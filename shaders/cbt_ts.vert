#version 450
#extension GL_GOOGLE_include_directive : require
// cbt-ts (schemes/cbt_ts.cpp): a leaf of cbt's tree as one triangle patch. The footprint's three
// vertices select the leaf's corners a, b, c (as control points 0, 1, 2) from its instance record.
#include "common.glsl"

layout(location = 0) in vec2 inLattice;  // (1, 0): a, (0, 0): b, (0, 1): c
struct InstanceRecord {
  vec4 a;
  vec4 b;
};
layout(set = 0, binding = LB_BINDING_INSTANCES, std430) readonly buffer Instances { InstanceRecord records[]; }
instances;

layout(location = 0) out vec2 outCorner;
layout(location = 1) out float outSquare;

void main() {
  InstanceRecord r = instances.records[gl_InstanceIndex];
  outCorner = inLattice.x > 0.5 ? r.a.xy : (inLattice.y > 0.5 ? r.b.xy : r.a.zw);
  outSquare = r.b.w;
}
