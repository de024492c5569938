#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP of every pixel from both images' planes (harness/metrics/gpu_flip.h), as
// harness/metrics/flip.cpp flipPixel combines them.
#include "flip_common.glsl"

layout(local_size_x = LB_FLIP_GROUP, local_size_y = LB_FLIP_GROUP) in;

float plane(uint i, uint p, uint at) { return planes[planeBase(i, p) + at]; }

void main() {
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (x >= pc.width || y >= pc.height) return;
  const uint at = y * pc.width + x;
  vec3 d = vec3(plane(0u, LB_FLIP_LAB, at) - plane(1u, LB_FLIP_LAB, at),
                plane(0u, LB_FLIP_LAB + 1u, at) - plane(1u, LB_FLIP_LAB + 1u, at),
                plane(0u, LB_FLIP_LAB + 2u, at) - plane(1u, LB_FLIP_LAB + 2u, at));
  const float cmax = k[LB_FLIP_K_CMAX], knee = 0.4 * cmax;
  float c = pow(abs(d.x) + length(d.yz), 0.7);
  float colour = c < knee ? 0.95 / knee * c : 0.95 + (c - knee) / (cmax - knee) * (1.0 - 0.95);
  float f = max(abs(plane(0u, LB_FLIP_EDGE, at) - plane(1u, LB_FLIP_EDGE, at)),
                abs(plane(0u, LB_FLIP_POINT, at) - plane(1u, LB_FLIP_POINT, at)));
  float feature = sqrt(f / sqrt(2.0));
  flipMap[at] = colour > 0.0 ? pow(colour, 1.0 - feature) : 0.0;
}
