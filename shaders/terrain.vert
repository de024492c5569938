#version 450
#extension GL_GOOGLE_include_directive : require
// Pass-through of the grid point, displaced so LOD decisions see real heights (NVIDIA sample).
#include "common.glsl"

layout(location = 0) in vec2 inXZ;
layout(location = 0) out vec3 outPos;

void main() {
  outPos = vec3(inXZ.x, terrainHeight(inXZ), inXZ.y);
}
