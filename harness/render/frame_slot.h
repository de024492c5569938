#pragma once
// One frame in flight of the renderer's ring (render/renderer.h): its command buffer and fence, and
// what the frame's results need once the fence has signalled.
#include "vk/resources.h"

namespace lb {

struct FrameSlot {
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // released with the renderer's command pool
  vk::Unique<VkFence> fence;
  bool busy = false, readback = false;
  int frame = 0;
  double cpuMs = 0;
  double harnessMs = 0;  // host time spent in submitFrame (uniforms, recording, submit)
  double prepareMs = 0;  // host time of the path's prepare() (the instanced path's selection)
  // renderInto's destination of the read-back copy; null: the renderer's read-back buffer.
  const Buffer* target = nullptr;
};

}  // namespace lb
