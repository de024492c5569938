#version 450
#extension GL_GOOGLE_include_directive : require
// cbt, pass 2 of 4 (several dispatches): the sum reduction. A dispatch computes level START, from
// the bitfield's words (START = D - 5, also copying them for the next update's reads) or from the
// level below, and folds five levels above it in shared memory, 32 nodes a workgroup; the next
// dispatch starts six levels up.
#include "cbt.glsl"

layout(constant_id = 0) const uint START = 0u;
layout(local_size_x = 32) in;

shared uint partial[32];

void main() {
  uint t = gl_LocalInvocationID.x, n = gl_GlobalInvocationID.x;
  uint sums = cbtSums();
  uint v = 0u;
  if (n < (1u << START)) {
    if (START + 5u == cbtDepth()) {
      uint w = state.words[LB_CBT_HEADER + n];
      state.words[cbtRead() + n] = w;
      v = bitCount(w);
    } else
      v = state.words[sums + (2u << START) + 2u * n] + state.words[sums + (2u << START) + 2u * n + 1u];
    state.words[sums + (1u << START) + n] = v;
  }
  partial[t] = v;
  barrier();
  for (uint k = 1u; k <= 5u && k <= START; ++k) {
    uint width = 32u >> k;
    uint x = t < width ? partial[2u * t] + partial[2u * t + 1u] : 0u;
    barrier();
    partial[t] = x;
    barrier();
    uint node = gl_WorkGroupID.x * width + t, level = START - k;
    if (t < width && node < (1u << level)) state.words[sums + (1u << level) + node] = x;
  }
}
