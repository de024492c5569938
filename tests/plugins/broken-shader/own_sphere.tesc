#version 450
#extension GL_GOOGLE_include_directive : require
// own_sphere.tesc with a mistake a user makes: a name the shared includes do not define.
#include "common.glsl"
#include "tesc_common.glsl"

void main() {
  passThrough();
  writeLevels(vec4(undefinedTriangleSize), vec2(1.0));
}
