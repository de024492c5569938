#version 450
#extension GL_GOOGLE_include_directive : require
// Flat triangle evaluation: terrain_tri.tese without the Phong term (inputs are the same). The
// reference a phong render at shape factor 0 must match bit for bit (tests/test_scheme_phong.cpp).
#include "terrain_vertex.glsl"
#include "tri_eval.glsl"

void main() { emitVertex(flatPoint()); }
