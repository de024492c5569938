#version 450
#extension GL_GOOGLE_include_directive : require
// cbt, pass 3 of 4, one thread: the leaf count the reduction left becomes the draw's instance count
// (up to the records' capacity; the rest is counted as overflow) and the size of the next per-leaf
// dispatches; the update count moves on, alternating split and merge.
#include "cbt.glsl"

layout(set = 0, binding = LB_BINDING_LOD_ARGS, std430) buffer LodArgs {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  int vertexOffset;
  uint firstInstance;
}
args;

layout(local_size_x = 1) in;

void main() {
  uint leaves = cbtLeaves();
  uint drawn = min(leaves, state.words[LB_CBT_CAPACITY]);
  state.words[LB_CBT_LEAVES] = leaves;
  state.words[LB_CBT_OVERFLOW] = leaves - drawn;
  state.words[LB_CBT_DISPATCH] = (leaves + LB_CBT_GROUP - 1u) / LB_CBT_GROUP;
  state.words[LB_CBT_DISPATCH + 1] = 1u;
  state.words[LB_CBT_DISPATCH + 2] = 1u;
  state.words[LB_CBT_UPDATES] += 1u;
  args.indexCount = state.words[LB_CBT_INDEX_COUNT];
  args.instanceCount = drawn;
  args.firstIndex = 0u;
  args.vertexOffset = 0;
  args.firstInstance = 0u;
}
