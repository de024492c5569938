#include "metrics/raycast_shade.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "terrain/normal_map.h"

namespace lb {

namespace {

float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

uint8_t unorm8(float v) {
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

glm::vec3 shadeLight() {
  return glm::normalize(glm::vec3(0.4f, 0.8f, 0.3f));  // Renderer::fillUniforms (harness/render/renderer.cpp)
}

std::array<uint8_t, 4> shadeTerrain(const NormalMap& normals, float extent, float x, float z, float level) {
  glm::vec3 n = sampleNormalMap(normals, extent, x, z, level);  // terrain.frag mapNormal()
  static const glm::vec3 light = shadeLight();
  float diffuse = std::max(glm::dot(n, light), 0.0f);
  float shade = 0.25f + 0.75f * diffuse;
  float slope = 1.0f - n.y;
  glm::vec3 base = glm::mix(glm::vec3(0.36f, 0.45f, 0.25f), glm::vec3(0.45f, 0.40f, 0.35f),
                            smoothstep(kSlopeBlendLow, kSlopeBlendHigh, slope));
  glm::vec3 c = base * shade;
  return {unorm8(c.r), unorm8(std::max(c.g, 0.02f)), unorm8(c.b), 255};
}

}  // namespace lb
