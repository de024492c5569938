// Mean SSIM of luma as image_metrics.cpp ssim() computes it (11x11 Gaussian, valid windows only),
// in REAL: double where the device has shaderFloat64 (reduce_ssim_f64.comp), else float
// (reduce_ssim.comp) with luma shifted by LB_SSIM_SHIFT so the variances cancel less. A workgroup
// holds a 26x26 luma tile, filters it across then down in shared memory and writes the sum of its
// 16x16 windows' SSIM to its partial word(s); the host adds the partials.
#include "reduce_params.h"

layout(local_size_x = LB_RED_SSIM_TILE, local_size_y = LB_RED_SSIM_TILE) in;
layout(std430, set = 0, binding = LB_REDUCE_BINDING_A) readonly buffer ImageA { uint a[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_B) readonly buffer ImageB { uint b[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_RESULT) buffer Result { uint words[]; };
layout(std430, set = 0, binding = LB_REDUCE_BINDING_WEIGHTS) readonly buffer Weights {
  float wf[16];
#ifdef REDUCE_F64
  double wd[16];
#endif
};
#ifdef REDUCE_F64
#define W(i) wd[i]
#else
#define W(i) wf[i]
#endif

const uint kTile = LB_RED_SSIM_TILE, kTaps = 2u * LB_SSIM_RADIUS + 1u, kIn = kTile + kTaps - 1u;
shared REAL lx[kIn * kIn], ly[kIn * kIn];
shared REAL across[5][kIn * kTile];  // x, y, xx, yy, xy filtered along rows
shared REAL total[kTile * kTile];

REAL luma(uint p) {
  return W(LB_SSIM_LUMA) * REAL(p & 0xffu) + W(LB_SSIM_LUMA + 1) * REAL((p >> 8u) & 0xffu) +
         W(LB_SSIM_LUMA + 2) * REAL((p >> 16u) & 0xffu) - SHIFT;
}

void main() {
  uint t = gl_LocalInvocationIndex;
  uvec2 origin = gl_WorkGroupID.xy * kTile;
  for (uint i = t; i < kIn * kIn; i += kTile * kTile) {
    // Texels past the image feed only windows past the valid area: clamp them to stay in bounds.
    uint x = min(origin.x + i % kIn, pc.width - 1u), y = min(origin.y + i / kIn, pc.height - 1u);
    lx[i] = luma(a[y * pc.width + x]);
    ly[i] = luma(b[y * pc.width + x]);
  }
  barrier();
  for (uint i = t; i < kIn * kTile; i += kTile * kTile) {
    uint row = i / kTile, col = i % kTile;
    REAL s[5] = REAL[5](0, 0, 0, 0, 0);
    for (uint k = 0u; k < kTaps; ++k) {
      REAL w = W(k), x = lx[row * kIn + col + k], y = ly[row * kIn + col + k];
      s[0] += w * x;
      s[1] += w * y;
      s[2] += w * (x * x);
      s[3] += w * (y * y);
      s[4] += w * (x * y);
    }
    for (uint q = 0u; q < 5u; ++q) across[q][i] = s[q];
  }
  barrier();
  uvec2 l = gl_LocalInvocationID.xy;
  REAL f[5] = REAL[5](0, 0, 0, 0, 0);
  for (uint k = 0u; k < kTaps; ++k)
    for (uint q = 0u; q < 5u; ++q) f[q] += W(k) * across[q][(l.y + k) * kTile + l.x];
  uvec2 pos = origin + l;
  REAL v = 0;
  if (pos.x + kTaps - 1u < pc.width && pos.y + kTaps - 1u < pc.height) {
    REAL vx = f[2] - f[0] * f[0], vy = f[3] - f[1] * f[1], cov = f[4] - f[0] * f[1];
    REAL mx = f[0] + SHIFT, my = f[1] + SHIFT, c1 = W(LB_SSIM_C1), c2 = W(LB_SSIM_C2);
    v = ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
  }
  total[t] = v;
  barrier();
  for (uint span = kTile * kTile / 2u; span > 0u; span /= 2u) {
    if (t < span) total[t] += total[t + span];
    barrier();
  }
  if (t == 0u) {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
#ifdef REDUCE_F64
    uvec2 bits = unpackDouble2x32(total[0]);
    words[LB_RED_PARTIALS + 2u * group] = bits.x;
    words[LB_RED_PARTIALS + 2u * group + 1u] = bits.y;
#else
    words[LB_RED_PARTIALS + group] = floatBitsToUint(total[0]);
#endif
  }
}
