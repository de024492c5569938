#include "camera/camera_matrices.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "camera/camera_path.h"

namespace lb {

CameraMatrices cameraMatrices(const CameraPose& pose, float aspect, float extent) {
  CameraMatrices m;
  m.eye = pose.eye;
  glm::vec3 dir = pose.target - pose.eye;
  // Looking straight down makes lookAt's up vector degenerate; pick another one then.
  glm::vec3 up = std::abs(glm::normalize(dir).y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  m.view = glm::lookAt(pose.eye, pose.target, up);
  m.proj = glm::perspective(glm::radians(pose.fovDeg), aspect, extent * 1e-4f, extent * 4.0f);
  m.proj[1][1] *= -1.0f;  // Vulkan clip space has y down
  return m;
}

void frustumPlanes(const glm::mat4& vp, glm::vec4 planes[6]) {
  glm::vec4 r0(vp[0][0], vp[1][0], vp[2][0], vp[3][0]), r1(vp[0][1], vp[1][1], vp[2][1], vp[3][1]),
      r2(vp[0][2], vp[1][2], vp[2][2], vp[3][2]), r3(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
  planes[0] = r3 + r0;
  planes[1] = r3 - r0;
  planes[2] = r3 + r1;
  planes[3] = r3 - r1;
  planes[4] = r2;  // depth in [0,1]
  planes[5] = r3 - r2;
  for (int i = 0; i < 6; ++i) planes[i] /= glm::length(glm::vec3(planes[i]));
}

}  // namespace lb
