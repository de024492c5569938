#version 450
#extension GL_GOOGLE_include_directive : require
// cbt, pass 3 of 4, one thread: the leaf count the reduction left becomes the draw's instance count
// and the size of the next per-leaf dispatches, both up to the records' capacity (the leaves past it
// are neither updated nor drawn, and counted as overflow: the case fails, and no dispatch outgrows
// the device's limit); the update count moves on, alternating split and merge. PER_DRAW > 0 (cbt-ts): the
// instances are split into draws of at most PER_DRAW, ceil(capacity / PER_DRAW) commands of room
// and their count after them (vkCmdDrawIndexedIndirectCount).
#include "cbt.glsl"

layout(constant_id = 0) const uint PER_DRAW = 0u;
layout(set = 0, binding = LB_BINDING_LOD_ARGS, std430) buffer LodArgs { uint words[]; }
args;

layout(local_size_x = 1) in;

void command(uint k, uint instances, uint first) {
  args.words[5u * k] = state.words[LB_CBT_INDEX_COUNT];
  args.words[5u * k + 1u] = instances;
  args.words[5u * k + 2u] = 0u;
  args.words[5u * k + 3u] = 0u;
  args.words[5u * k + 4u] = first;
}

void main() {
  uint leaves = cbtLeaves();
  uint capacity = state.words[LB_CBT_CAPACITY];
  uint drawn = min(leaves, capacity);
  state.words[LB_CBT_LEAVES] = leaves;
  state.words[LB_CBT_OVERFLOW] = leaves - drawn;
  state.words[LB_CBT_DISPATCH] = (drawn + LB_CBT_GROUP - 1u) / LB_CBT_GROUP;
  state.words[LB_CBT_DISPATCH + 1] = 1u;
  state.words[LB_CBT_DISPATCH + 2] = 1u;
  state.words[LB_CBT_UPDATES] += 1u;
  if (PER_DRAW == 0u) {
    command(0u, drawn, 0u);
    return;
  }
  uint draws = (drawn + PER_DRAW - 1u) / PER_DRAW;
  for (uint k = 0u; k < draws; ++k) command(k, min(PER_DRAW, drawn - k * PER_DRAW), k * PER_DRAW);
  args.words[5u * ((capacity + PER_DRAW - 1u) / PER_DRAW)] = draws;
}
