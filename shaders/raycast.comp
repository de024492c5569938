#version 450
#extension GL_GOOGLE_include_directive : require
// The ray-cast ground truth in double (shaderFloat64): harness/metrics/gpu_raycast.h.
#include "raycast.glsl"
