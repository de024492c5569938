#version 450
#extension GL_GOOGLE_include_directive : require
// SSIM in double, as the CPU computes it (reduce_ssim.glsl); needs shaderFloat64.
#define REDUCE_F64
#define REAL double
#define SHIFT 0.0lf
#include "reduce_ssim.glsl"
