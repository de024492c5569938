#pragma once
// A pose's view and projection in Vulkan conventions (y down in clip space, depth in [0, 1]), the
// one definition the renderer, the probe and the ray-cast truth share.
#include <glm/glm.hpp>

namespace lb {

struct CameraPose;

struct CameraMatrices {
  glm::mat4 view{1}, proj{1};
  glm::vec3 eye{0};
};
// Near and far planes follow the terrain's extent (1e-4 and 4 x extent).
CameraMatrices cameraMatrices(const CameraPose& pose, float aspect, float extent);
// The six planes of viewProj's frustum (x, y, then depth in [0, 1]), normalized, pointing inwards.
void frustumPlanes(const glm::mat4& viewProj, glm::vec4 planes[6]);

}  // namespace lb
