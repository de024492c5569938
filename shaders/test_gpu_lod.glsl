// TEST ONLY (tests/gpu_lod_scheme.h): the GPU-indirect path's buffers as its compute passes see them.
// State: [0] updates run since the last reset, [1] [2] the terrain's min and max height (float bits),
// [3] the footprint's index count.
#include "shared.h"

layout(set = 0, binding = LB_BINDING_LOD_STATE, std430) buffer LodState { uint words[]; }
state;
layout(set = 0, binding = LB_BINDING_LOD_ARGS, std430) buffer LodArgs {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  int vertexOffset;
  uint firstInstance;
}
args;
struct InstanceRecord {
  vec4 a;
  vec4 b;
};
layout(set = 0, binding = LB_BINDING_INSTANCES, std430) writeonly buffer Instances { InstanceRecord records[]; }
instances;
