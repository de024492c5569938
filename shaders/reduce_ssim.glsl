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
// x, y, xx, yy, xy filtered along rows (named, not indexed: a compiler may put indexed locals in memory)
shared REAL hx[kIn * kTile], hy[kIn * kTile], hxx[kIn * kTile], hyy[kIn * kTile], hxy[kIn * kTile];
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
    uint at = (i / kTile) * kIn + i % kTile;
    REAL sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (uint k = 0u; k < kTaps; ++k) {
      REAL w = W(k), x = lx[at + k], y = ly[at + k];
      sx += w * x;
      sy += w * y;
      sxx += w * (x * x);
      syy += w * (y * y);
      sxy += w * (x * y);
    }
    hx[i] = sx;
    hy[i] = sy;
    hxx[i] = sxx;
    hyy[i] = syy;
    hxy[i] = sxy;
  }
  barrier();
  uvec2 l = gl_LocalInvocationID.xy;
  REAL mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
  for (uint k = 0u; k < kTaps; ++k) {
    uint at = (l.y + k) * kTile + l.x;
    REAL w = W(k);
    mx += w * hx[at];
    my += w * hy[at];
    sxx += w * hxx[at];
    syy += w * hyy[at];
    sxy += w * hxy[at];
  }
  uvec2 pos = origin + l;
  REAL v = 0;
  if (pos.x + kTaps - 1u < pc.width && pos.y + kTaps - 1u < pc.height) {
    REAL vx = sxx - mx * mx, vy = syy - my * my, cov = sxy - mx * my, c1 = W(LB_SSIM_C1), c2 = W(LB_SSIM_C2);
    mx += SHIFT;
    my += SHIFT;
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
