#version 450
#extension GL_GOOGLE_include_directive : require
// Minimal loop, attribution variant (`probe --vertex-height`): the grid point displaced as
// lodbench's terrain.vert does, so the probe pays the control-point height fetch lodbench's LOD
// decisions need.
#include "probe.glsl"

layout(location = 0) in vec2 inXZ;
layout(location = 0) out vec3 outPos;

void main() { outPos = vec3(inXZ.x, probeHeight(inXZ), inXZ.y); }
