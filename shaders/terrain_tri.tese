#version 450
#extension GL_GOOGLE_include_directive : require
// Shared evaluation shader for triangle patches: Phong tessellation (Boubekeur & Alexa 2008;
// Rapp 2011, 5.2.4 and Figure 5-13). The position is the Phong surface itself, not the heightfield:
// the thesis replaces displacement by Phong geometry, so the heightfield is read only at the corners.
// Shape factor alpha (inShape, from the control shader): 0 = flat triangles, 1 = full Phong.
#include "terrain_vertex.glsl"
#include "tri_eval.glsl"
#include "phong.glsl"

void main() {
  vec3 onTriangle = flatPoint();
  vec3 phong = phongPoint(onTriangle, gl_TessCoord, inPos[0], inPos[1], inPos[2], inNormal[0], inNormal[1], inNormal[2]);
  // lerp(flat, phong, alpha) written so that alpha = 0 and the corners (phong == flat) are exact.
  precise vec3 world = onTriangle + inShape * (phong - onTriangle);
  emitVertex(world);
}
