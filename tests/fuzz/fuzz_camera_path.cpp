// libFuzzer target: the camera-path CSV parser, then sampling the parsed path (interpolation and
// the ground clamp read every keyframe). Bad input must end in lb::InputError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "camera/camera_path.h"
#include "error.h"
#include "terrain/heightfield.h"

extern size_t lbFuzzInputSize;  // fccp_buffer.cpp: how much of the CSV reader's buffer to open

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lbFuzzInputSize = size;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    lb::CameraPath path = lb::parseCameraPath(text, "fuzz.csv");
    static const lb::Heightfield flat = [] {
      lb::Heightfield h;
      h.width = h.height = 2;
      h.h.assign(4, 0.0f);
      return h;
    }();
    const int frames = lb::frameCount(path, 30);
    for (int f : {0, frames / 2, frames - 1}) (void)lb::samplePose(path, 30, f, flat);
  } catch (const lb::InputError&) {
  }
  return 0;
}
