// Shared by the FLIP passes (shaders/flip_*.comp): the buffers and the colour spaces, as
// harness/metrics/flip_color.h computes them.
#include "flip_params.h"

layout(std430, set = 0, binding = LB_FLIP_BINDING_A) readonly buffer ImageA { uint imageA[]; };
layout(std430, set = 0, binding = LB_FLIP_BINDING_B) readonly buffer ImageB { uint imageB[]; };
layout(std430, set = 0, binding = LB_FLIP_BINDING_PLANES) buffer Planes { float planes[]; };
layout(std430, set = 0, binding = LB_FLIP_BINDING_KERNELS) readonly buffer Kernels { float k[]; };
layout(std430, set = 0, binding = LB_FLIP_BINDING_MAP) buffer Map { float flipMap[]; };

uint pixels() { return pc.width * pc.height; }
// Plane p of image i.
uint planeBase(uint i, uint p) { return (i * LB_FLIP_PLANES + p) * pixels(); }

const mat3 kRgbToXyz = mat3(0.4124564, 0.2126729, 0.0193339, 0.3575761, 0.7151522, 0.1191920, 0.1804375,
                            0.0721750, 0.9503041);  // columns
const mat3 kXyzToRgb = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314,
                            0.0415560, 1.0572252);
const vec3 kWhite = vec3(0.4124564 + 0.3575761 + 0.1804375, 0.2126729 + 0.7151522 + 0.0721750,
                         0.0193339 + 0.1191920 + 0.9503041);

vec3 xyzToYcxcz(vec3 xyz) {
  vec3 n = xyz / kWhite;
  return vec3(116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z));
}
vec3 ycxczToXyz(vec3 o) {
  float y = (o.x + 16.0) / 116.0, x = o.y / 500.0 + y, z = y - o.z / 200.0;
  return vec3(x, y, z) * kWhite;
}
float labF(float t) {
  const float d = 6.0 / 29.0;
  return t > d * d * d ? pow(t, 1.0 / 3.0) : t / (3.0 * d * d) + 4.0 / 29.0;
}
vec3 huntLab(vec3 xyz) {
  float fx = labF(xyz.x / kWhite.x), fy = labF(xyz.y / kWhite.y), fz = labF(xyz.z / kWhite.z);
  float l = 116.0 * fy - 16.0;
  return vec3(l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz));
}

// A pixel of image i as YCxCz, the clear colour seen as the sky of images for people (flip.h asSeen).
vec3 ycxczAt(uint i, int x, int y) {
  x = clamp(x, 0, int(pc.width) - 1);
  y = clamp(y, 0, int(pc.height) - 1);
  uint idx = uint(y) * pc.width + uint(x);
  uint p = i == 0u ? imageA[idx] : imageB[idx];
  if ((p & 0xffffffu) == 0xff00ffu) p = 196u | (210u << 8) | (226u << 16);
  vec3 rgb = vec3(k[LB_FLIP_K_LINEAR + (p & 255u)], k[LB_FLIP_K_LINEAR + ((p >> 8) & 255u)],
                  k[LB_FLIP_K_LINEAR + ((p >> 16) & 255u)]);
  return xyzToYcxcz(kRgbToXyz * rgb);
}
