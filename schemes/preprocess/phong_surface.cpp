#include "schemes/preprocess/phong_surface.h"

namespace lb {

glm::vec3 phongProjection(glm::vec3 p, glm::vec3 corner, glm::vec3 normal) {
  return p - glm::dot(p - corner, normal) * normal;
}

static glm::vec3 flatPoint(const PhongTriangle& t, glm::vec3 b) {
  return b.x * t.pos[0] + b.y * t.pos[1] + b.z * t.pos[2];
}

glm::vec3 phongPoint(const PhongTriangle& t, glm::vec3 b) {
  glm::vec3 p = flatPoint(t, b);
  return b.x * phongProjection(p, t.pos[0], t.normal[0]) + b.y * phongProjection(p, t.pos[1], t.normal[1]) +
         b.z * phongProjection(p, t.pos[2], t.normal[2]);
}

glm::vec3 phongSurface(const PhongTriangle& t, glm::vec3 b, float alpha) {
  glm::vec3 flat = flatPoint(t, b);
  return flat + alpha * (phongPoint(t, b) - flat);
}

}  // namespace lb
