#version 450
#extension GL_GOOGLE_include_directive : require
// SSIM in float, for devices without shaderFloat64 (reduce_ssim.glsl).
#define REAL float
#define SHIFT float(LB_SSIM_SHIFT)
#include "reduce_ssim.glsl"
