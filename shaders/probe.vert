#version 450
#extension GL_GOOGLE_include_directive : require
// Minimal loop: the grid point, passed through.
#include "probe.glsl"

layout(location = 0) in vec2 inXZ;
layout(location = 0) out vec2 outXZ;

void main() { outXZ = inXZ; }
