// GPU reductions of images and error maps (harness/metrics/gpu_reduce.h, shaders/reduce_*.comp):
// bindings, the result buffer's layout in 32-bit words and the push constants, read by C++ and GLSL.
#ifndef LB_REDUCE_PARAMS_H
#define LB_REDUCE_PARAMS_H
#define LB_REDUCE_BINDING_A 0        // image a (RGBA8 as uint) or the error map (float bits as uint)
#define LB_REDUCE_BINDING_B 1        // image b (RGBA8 as uint)
#define LB_REDUCE_BINDING_RESULT 2   // the words below, device-local, cleared before every call
#define LB_REDUCE_BINDING_WEIGHTS 3  // SSIM constants: float[16] then double[16] (LB_SSIM_*)

// Sums that can pass 2^32 are two words (low, high): a workgroup adds its total to the low word
// and carries into the high one, so they stay exact integers.
#define LB_RED_SUM_SQ 0   // squared RGB differences
#define LB_RED_SUM_ABS 2  // absolute RGB differences
#define LB_RED_OVER 4     // pixels whose largest channel difference exceeds the threshold
#define LB_RED_CHANGED 5  // pixels with any channel difference
#define LB_RED_MISSING 6  // clear in a, terrain in b
#define LB_RED_EXTRA 7    // terrain in a, clear in b
#define LB_RED_CANDIDATES 8
#define LB_RED_ERR_COUNT 9
#define LB_RED_ERR_MAX 10        // largest value's bits (non-negative floats order as their bits)
#define LB_RED_ERR_SELECT 11     // 3 words: the coarse bins holding the ranks around the p95
#define LB_RED_TRUTH_TERRAIN 14  // terrain in b
#define LB_RED_HEADER 16
#define LB_RED_DIFF_HIST 16     // 256 bins of the largest channel difference (bin 0 left empty)
#define LB_RED_COARSE_HIST 272  // 256 bins: the error's exponent (bits >> 23)
#define LB_RED_FINE_HIST 528    // 3 x 1024 bins: 10 mantissa bits inside each selected exponent
#define LB_RED_FINE_BINS 1024
#define LB_RED_PARTIALS 3600  // one sum per workgroup: SSIM (double: 2 words, or float) or error (float)

#define LB_RED_IMAGE_GROUP 256      // threads of the image and error passes
#define LB_RED_IMAGE_PER_THREAD 16  // pixels a thread of the image pass reads
#define LB_RED_ERROR_PER_THREAD 4   // values a thread of the error passes reads (bounds float rounding)
#define LB_RED_SSIM_TILE 16         // SSIM outputs per workgroup side

#define LB_SSIM_RADIUS 5  // 11x11 window
#define LB_SSIM_LUMA 11   // three luma weights at [11..13]
#define LB_SSIM_C1 14
#define LB_SSIM_C2 15
#define LB_SSIM_SHIFT 128.0  // the float pass subtracts it from luma before squaring (less cancellation)

#ifdef __cplusplus
#include <cstdint>
namespace lb {
struct ReducePush {
  uint32_t width, height, threshold, reach;
};
static_assert(sizeof(ReducePush) == 16, "push constant mirror");
}  // namespace lb
#else
layout(push_constant) uniform ReducePush {
  uint width;
  uint height;
  uint threshold;
  uint reach;
}
pc;
#endif
#endif
