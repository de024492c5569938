#pragma once
// Phong tessellation (Boubekeur & Alexa 2008; Rapp 2011, Figure 5-13), the surface the phong scheme
// renders: shaders/phong.glsl and terrain_tri.tese do the same arithmetic on the GPU.
#include <glm/glm.hpp>

namespace lb {

struct PhongTriangle {
  glm::vec3 pos[3];
  glm::vec3 normal[3];  // unit length
};

// p moved onto the plane through `corner` perpendicular to `normal`.
glm::vec3 phongProjection(glm::vec3 p, glm::vec3 corner, glm::vec3 normal);
// The full Phong point for barycentric coordinates b (b.x + b.y + b.z = 1): the flat point projected
// onto each corner's tangent plane, the projections interpolated with b.
glm::vec3 phongPoint(const PhongTriangle& t, glm::vec3 b);
// flat + alpha * (phong - flat): exactly the flat point at alpha = 0 and exactly a corner at a corner.
glm::vec3 phongSurface(const PhongTriangle& t, glm::vec3 b, float alpha);

}  // namespace lb
