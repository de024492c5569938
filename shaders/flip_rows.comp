#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's filters along rows (harness/metrics/gpu_flip.h): each channel of image pc.image with its
// contrast-sensitivity kernels, and the achromatic channel with the detectors' three kernels, taps
// summed in kernel order as the CPU oracle sums them.
#include "flip_common.glsl"

layout(local_size_x = LB_FLIP_GROUP, local_size_y = LB_FLIP_GROUP) in;

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(pc.width) || y >= int(pc.height)) return;
  const int r = int(pc.csfRadius), fr = int(pc.featureRadius), n = 2 * r + 1, fn = 2 * fr + 1;
  const uint kc = LB_FLIP_K_KERNELS, kf = kc + 4u * uint(n);
  float a = 0, rg = 0, by1 = 0, by2 = 0;
  for (int i = 0; i < n; ++i) {
    vec3 o = ycxczAt(pc.image, x + i - r, y);
    a += k[kc + uint(i)] * o.x;
    rg += k[kc + uint(n + i)] * o.y;
    by1 += k[kc + uint(2 * n + i)] * o.z;
    by2 += k[kc + uint(3 * n + i)] * o.z;
  }
  float e = 0, g = 0, p = 0;
  for (int i = 0; i < fn; ++i) {
    float lum = (ycxczAt(pc.image, x + i - fr, y).x + 16.0) / 116.0;
    g += k[kf + uint(i)] * lum;
    e += k[kf + uint(fn + i)] * lum;
    p += k[kf + uint(2 * fn + i)] * lum;
  }
  const uint at = uint(y) * pc.width + uint(x);
  planes[planeBase(pc.image, LB_FLIP_ROW_A) + at] = a;
  planes[planeBase(pc.image, LB_FLIP_ROW_RG) + at] = rg;
  planes[planeBase(pc.image, LB_FLIP_ROW_BY1) + at] = by1;
  planes[planeBase(pc.image, LB_FLIP_ROW_BY2) + at] = by2;
  planes[planeBase(pc.image, LB_FLIP_ROW_EDGE) + at] = e;
  planes[planeBase(pc.image, LB_FLIP_ROW_GAUSS) + at] = g;
  planes[planeBase(pc.image, LB_FLIP_ROW_POINT) + at] = p;
}
