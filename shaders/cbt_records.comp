#version 450
#extension GL_GOOGLE_include_directive : require
// cbt, pass 4 of 4, one thread per leaf: the leaf's triangle as its instance record, so the vertex
// shader finds it by gl_InstanceIndex alone: a = (corner a, right-angle corner b), b = (corner c,
// depth, 2^L), lattice units.
#include "cbt.glsl"

struct InstanceRecord {
  vec4 a;
  vec4 b;
};
layout(set = 0, binding = LB_BINDING_INSTANCES, std430) writeonly buffer Instances { InstanceRecord records[]; }
instances;

layout(local_size_x = LB_CBT_GROUP) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= min(state.words[LB_CBT_LEAVES], state.words[LB_CBT_CAPACITY])) return;
  uint id = cbtLeaf(i);
  ivec2 a, b, c;
  cbtTriangle(id, a, b, c);
  float g = float(1 << int(state.words[LB_CBT_LATTICE_LOG2]));
  instances.records[i].a = vec4(vec2(a), vec2(b));
  instances.records[i].b = vec4(vec2(c), float(findMSB(id)), g);
}
