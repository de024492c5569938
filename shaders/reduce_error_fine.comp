#version 450
#extension GL_GOOGLE_include_directive : require
// Error map, pass 3 of 3: inside each selected exponent bin, a histogram of the next 10 mantissa
// bits (LB_RED_FINE_BINS bins): a bin spans 2^-10 of its values' magnitude.
#include "reduce_error.glsl"

layout(local_size_x = LB_RED_IMAGE_GROUP) in;
shared uint fine[3 * LB_RED_FINE_BINS];

void main() {
  uint t = gl_LocalInvocationID.x;
  for (uint i = t; i < 3u * LB_RED_FINE_BINS; i += LB_RED_IMAGE_GROUP) fine[i] = 0u;
  uvec3 select = uvec3(words[LB_RED_ERR_SELECT], words[LB_RED_ERR_SELECT + 1], words[LB_RED_ERR_SELECT + 2]);
  barrier();
  uint n = pc.width * pc.height, first = gl_WorkGroupID.x * (LB_RED_IMAGE_GROUP * LB_RED_ERROR_PER_THREAD);
  for (uint k = 0u; k < LB_RED_ERROR_PER_THREAD; ++k) {
    uint i = first + k * LB_RED_IMAGE_GROUP + t, bits;
    if (i >= n || !errorValue(i, bits)) continue;
    uint c = bits >> 23u, mantissa = (bits >> 13u) & (LB_RED_FINE_BINS - 1u);
    // The first of equal selections takes the value, as the host reads them.
    for (uint j = 0u; j < 3u; ++j)
      if (c == select[j]) {
        atomicAdd(fine[j * LB_RED_FINE_BINS + mantissa], 1u);
        break;
      }
  }
  barrier();
  for (uint i = t; i < 3u * LB_RED_FINE_BINS; i += LB_RED_IMAGE_GROUP)
    if (fine[i] > 0u) atomicAdd(words[LB_RED_FINE_HIST + i], fine[i]);
}
