#version 450
#extension GL_GOOGLE_include_directive : require
// Error map, pass 1 of 3 (metrics/gpu_reduce.h): count, sum, max and the histogram of exponents.
// The sum is a float per workgroup, added pairwise in shared memory: each of its 1024 values goes
// through at most 3 + 8 roundings, so its relative error stays under 11 x 2^-24 < 1e-6 (all values
// are >= 0); the host adds the partials in double.
#include "reduce_error.glsl"

layout(local_size_x = LB_RED_IMAGE_GROUP) in;
shared uint coarse[256];
shared float sums[LB_RED_IMAGE_GROUP];
shared uint count, maxBits;

void main() {
  uint t = gl_LocalInvocationID.x;
  coarse[t] = 0u;
  if (t == 0u) {
    count = 0u;
    maxBits = 0u;
  }
  barrier();
  uint n = pc.width * pc.height, first = gl_WorkGroupID.x * (LB_RED_IMAGE_GROUP * LB_RED_ERROR_PER_THREAD);
  uint c = 0u, m = 0u;
  float s = 0.0;
  for (uint k = 0u; k < LB_RED_ERROR_PER_THREAD; ++k) {
    uint i = first + k * LB_RED_IMAGE_GROUP + t, bits;
    if (i >= n || !errorValue(i, bits)) continue;
    ++c;
    s += uintBitsToFloat(bits);
    m = max(m, bits);
    atomicAdd(coarse[bits >> 23u], 1u);
  }
  sums[t] = s;
  atomicAdd(count, c);
  atomicMax(maxBits, m);
  barrier();
  for (uint span = LB_RED_IMAGE_GROUP / 2u; span > 0u; span /= 2u) {
    if (t < span) sums[t] += sums[t + span];
    barrier();
  }
  if (coarse[t] > 0u) atomicAdd(words[LB_RED_COARSE_HIST + t], coarse[t]);
  if (t == 0u) {
    words[LB_RED_PARTIALS + gl_WorkGroupID.x] = floatBitsToUint(sums[0]);
    if (count > 0u) {
      atomicAdd(words[LB_RED_ERR_COUNT], count);
      atomicMax(words[LB_RED_ERR_MAX], maxBits);
    }
  }
}
