#version 450
#extension GL_GOOGLE_include_directive : require
// The ray-cast ground truth in float, for devices without shaderFloat64: harness/metrics/gpu_raycast.h.
#define LB_RAYCAST_F32 1
#include "raycast.glsl"
