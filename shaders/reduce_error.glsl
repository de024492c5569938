// The error map's values as the error passes read them (reduce_error*.comp): float bits, where -1
// marks a pixel without terrain. Statistics cover the values >= 0, as measure.cpp's summary does.
#include "reduce_params.h"

layout(std430, set = 0, binding = LB_REDUCE_BINDING_A) readonly buffer ErrorMap { uint e[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_RESULT) buffer Result { uint words[]; };

// Decided on the bits, so no denormal is flushed: +0 to +inf, and -0 (as +0); NaN and negatives are out.
bool errorValue(uint i, out uint bits) {
  bits = e[i];
  if (bits == 0x80000000u) bits = 0u;
  return bits <= 0x7f800000u;
}
