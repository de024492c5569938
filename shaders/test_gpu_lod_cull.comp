#version 450
#extension GL_GOOGLE_include_directive : require
// TEST ONLY: the second LOD pass: every base-grid patch whose box meets the culling frustum becomes
// one instance (record a.xy = patch index, as render/uniform_instanced.h places it), compacted with
// an atomic counter, so the GPU decides how many instances the indirect draw has.
#include "test_gpu_lod.glsl"

layout(local_size_x = 64) in;

bool outside(vec3 lo, vec3 hi) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = frame.frustum[i];
    vec3 v = vec3(p.x >= 0.0 ? hi.x : lo.x, p.y >= 0.0 ? hi.y : lo.y, p.z >= 0.0 ? hi.z : lo.z);
    if (dot(p.xyz, v) + p.w < 0.0) return true;
  }
  return false;
}

void main() {
  int grid = int(frame.terrain.y);
  for (int i = int(gl_GlobalInvocationID.x); i < grid * grid; i += int(gl_NumWorkGroups.x) * 64) {
    vec2 patchIndex = vec2(i % grid, i / grid);
    float side = frame.terrain.x / float(grid);
    vec2 lo = frame.origin.xy + patchIndex * side;
    vec3 boxLo = vec3(lo.x, uintBitsToFloat(state.words[1]), lo.y);
    vec3 boxHi = vec3(lo.x + side, uintBitsToFloat(state.words[2]), lo.y + side);
    if (outside(boxLo, boxHi)) continue;
    uint at = atomicAdd(args.instanceCount, 1u);
    instances.records[at].a = vec4(patchIndex, 0.0, 0.0);
    instances.records[at].b = vec4(0.0);
  }
}
