#version 450
#extension GL_GOOGLE_include_directive : require
// Measurement pass only: bins the exact screen-space area of every tessellated triangle
// (shaders/hist_count.glsl). Each input triangle is counted exactly once; rasterization is discarded.
#include "hist_count.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(location = 0) in vec3 inWorld[];
layout(location = 1) in float inLevel[];
layout(location = 0) out vec3 outWorld;
layout(location = 1) out float outLevel;

void main() {
  measureTriangle(gl_in[0].gl_Position, gl_in[1].gl_Position, gl_in[2].gl_Position, inWorld[0], inWorld[1],
                  inWorld[2]);
  // Mesa 22.3 lavapipe crashes when a geometry shader after tessellation emits nothing, so the
  // triangle passes through; the pipeline discards rasterization.
  for (int i = 0; i < 3; ++i) {
    gl_Position = gl_in[i].gl_Position;
    outWorld = inWorld[i];
    outLevel = inLevel[i];
    EmitVertex();
  }
  EndPrimitive();
}
