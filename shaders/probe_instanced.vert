#version 450
#extension GL_GOOGLE_include_directive : require
// Minimal instanced loop: one pre-tessellated patch (level x level cells) drawn grid^2 times, placed
// by gl_InstanceIndex, height from the height map: the tessellated probe's triangles without the
// tessellator.
#include "probe.glsl"

layout(location = 0) in vec2 inLattice;

void main() {
  float level = probe.terrain.y;
  int grid = int(probe.terrain.z);
  vec2 patchIndex = vec2(gl_InstanceIndex % grid, gl_InstanceIndex / grid);
  vec2 xz = (patchIndex * level + inLattice) * (probe.terrain.x / (float(grid) * level));
  gl_Position = probe.viewProj * vec4(xz.x, probeHeight(xz), xz.y, 1.0);
}
