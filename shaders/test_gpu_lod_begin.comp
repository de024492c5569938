#version 450
#extension GL_GOOGLE_include_directive : require
// TEST ONLY: the first LOD pass of a frame: empty draw arguments, one more update in the state.
#include "test_gpu_lod.glsl"

layout(local_size_x = 1) in;

void main() {
  args.indexCount = state.words[3];
  args.instanceCount = 0u;
  args.firstIndex = 0u;
  args.vertexOffset = 0;
  args.firstInstance = 0u;
  state.words[0] += 1u;
}
