#version 450
#extension GL_GOOGLE_include_directive : require
// Error map, pass 2 of 3: one workgroup finds the exponent bins that hold the sorted ranks
// floor(0.95 (n - 1)) - 1 .. + 1 (percentileSorted's two ranks, whichever way the host's double
// rank rounds), so pass 3 histograms only those values finely.
#include "reduce_params.h"

layout(local_size_x = 256) in;
layout(std430, set = 0, binding = LB_REDUCE_BINDING_RESULT) buffer Result { uint words[]; };
shared uint scan[256], selected[3];

void main() {
  uint t = gl_LocalInvocationID.x;
  uint own = words[LB_RED_COARSE_HIST + t];
  scan[t] = own;
  barrier();
  for (uint d = 1u; d < 256u; d *= 2u) {  // inclusive prefix sums
    uint v = t >= d ? scan[t - d] : 0u;
    barrier();
    scan[t] += v;
    barrier();
  }
  uint n = scan[255], below = scan[t] - own;
  if (t < 3u) selected[t] = 0xffffffffu;  // none: no value at all
  barrier();
  // The host checks that width x height x 95 fits 32 bits.
  uint lo = 95u * (max(n, 1u) - 1u) / 100u;
  for (uint j = 0u; j < 3u; ++j) {
    uint rank = clamp(lo + j, 1u, max(n, 1u)) - 1u;  // lo - 1 + j, clamped to [0, n - 1]
    if (rank >= below && rank < below + own) selected[j] = t;
  }
  barrier();
  if (t < 3u) words[LB_RED_ERR_SELECT + t] = selected[t];
}
