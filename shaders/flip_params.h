// LDR-FLIP's constants and the GPU pass's layout, shared by the CPU oracle (harness/metrics/flip.h),
// the config's default and the compute passes (shaders/flip_*.comp, harness/metrics/gpu_flip.h).
#ifndef LB_FLIP_PARAMS_H
#define LB_FLIP_PARAMS_H

// The paper's viewing condition: a 0.7 m wide 3840-pixel display seen from 0.7 m,
// 3840 / 0.7 x 0.7 x pi / 180 pixels per degree.
#define LB_FLIP_DEFAULT_PPD 67.0206432300439

#define LB_FLIP_BINDING_A 0        // the reference (truth), RGBA8 as uint
#define LB_FLIP_BINDING_B 1        // the test frame, RGBA8 as uint
#define LB_FLIP_BINDING_PLANES 2   // float planes of both images (LB_FLIP_PLANES each)
#define LB_FLIP_BINDING_KERNELS 3  // floats: the sRGB table, the blue-yellow shares, cmax, the kernels
#define LB_FLIP_BINDING_MAP 4      // the FLIP map, one float a pixel

// The kernels buffer: 256 linear values of sRGB bytes, then these, then the kernels (2r + 1 taps
// each): achromatic, red-green, blue-yellow 1 and 2 (r = csfRadius), gauss, edge, point (r = featureRadius).
#define LB_FLIP_K_LINEAR 0
#define LB_FLIP_K_BY_WEIGHT 256  // two shares
#define LB_FLIP_K_CMAX 258
#define LB_FLIP_K_KERNELS 260

// Planes of one image: after the row pass, then after the column pass.
#define LB_FLIP_ROW_A 0
#define LB_FLIP_ROW_RG 1
#define LB_FLIP_ROW_BY1 2
#define LB_FLIP_ROW_BY2 3
#define LB_FLIP_ROW_EDGE 4
#define LB_FLIP_ROW_GAUSS 5
#define LB_FLIP_ROW_POINT 6
#define LB_FLIP_LAB 7  // three planes: Hunt-adjusted L*, a*, b*
#define LB_FLIP_EDGE 10
#define LB_FLIP_POINT 11
#define LB_FLIP_PLANES 12

#define LB_FLIP_GROUP 16  // workgroups of 16 x 16 pixels

#ifdef __cplusplus
#include <cstdint>
namespace lb {
struct FlipPush {
  uint32_t width, height, csfRadius, featureRadius, image, pad0, pad1, pad2;
};
static_assert(sizeof(FlipPush) == 32, "push constant mirror");
}  // namespace lb
#else
layout(push_constant) uniform FlipPush {
  uint width;
  uint height;
  uint csfRadius;
  uint featureRadius;
  uint image;  // 0: the reference, 1: the test frame
  uint pad0;
  uint pad1;
  uint pad2;
}
pc;
#endif
#endif
