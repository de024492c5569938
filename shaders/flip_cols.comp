#version 450
#extension GL_GOOGLE_include_directive : require
// FLIP's filters along columns (harness/metrics/gpu_flip.h): the filtered colour to Hunt-adjusted
// L*a*b* (through linear RGB clamped to [0, 1]), and the edge and point magnitudes of image pc.image.
#include "flip_common.glsl"

layout(local_size_x = LB_FLIP_GROUP, local_size_y = LB_FLIP_GROUP) in;

float column(uint plane, uint kernel, int radius, int x, int y) {
  float s = 0;
  for (int i = 0; i <= 2 * radius; ++i) {
    int yy = clamp(y + i - radius, 0, int(pc.height) - 1);
    s += k[kernel + uint(i)] * planes[planeBase(pc.image, plane) + uint(yy) * pc.width + uint(x)];
  }
  return s;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(pc.width) || y >= int(pc.height)) return;
  const int r = int(pc.csfRadius), fr = int(pc.featureRadius), n = 2 * r + 1, fn = 2 * fr + 1;
  const uint kc = LB_FLIP_K_KERNELS, kf = kc + 4u * uint(n);
  float fy = column(LB_FLIP_ROW_A, kc, r, x, y), fcx = column(LB_FLIP_ROW_RG, kc + uint(n), r, x, y);
  float z = k[LB_FLIP_K_BY_WEIGHT] * column(LB_FLIP_ROW_BY1, kc + uint(2 * n), r, x, y) +
            k[LB_FLIP_K_BY_WEIGHT + 1u] * column(LB_FLIP_ROW_BY2, kc + uint(3 * n), r, x, y);
  vec3 rgb = clamp(kXyzToRgb * ycxczToXyz(vec3(fy, fcx, z)), 0.0, 1.0);
  vec3 lab = huntLab(kRgbToXyz * rgb);
  float ex = column(LB_FLIP_ROW_EDGE, kf, fr, x, y), ey = column(LB_FLIP_ROW_GAUSS, kf + uint(fn), fr, x, y);
  float px = column(LB_FLIP_ROW_POINT, kf, fr, x, y), py = column(LB_FLIP_ROW_GAUSS, kf + uint(2 * fn), fr, x, y);
  const uint at = uint(y) * pc.width + uint(x);
  planes[planeBase(pc.image, LB_FLIP_LAB) + at] = lab.x;
  planes[planeBase(pc.image, LB_FLIP_LAB + 1u) + at] = lab.y;
  planes[planeBase(pc.image, LB_FLIP_LAB + 2u) + at] = lab.z;
  planes[planeBase(pc.image, LB_FLIP_EDGE) + at] = length(vec2(ex, ey));
  planes[planeBase(pc.image, LB_FLIP_POINT) + at] = length(vec2(px, py));
}
