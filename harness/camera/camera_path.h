#pragma once
// Camera paths: CSV keyframes (time, eye xyz, target xyz, vertical fov in degrees), sampled at a
// fixed frame rate with Catmull-Rom interpolation. Coordinates are relative to the terrain:
// x and z are fractions of the extent ([0,1] covers the terrain), y is in units of the extent
// above the terrain's minimum height. The sampler keeps the eye above the ground.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lb {

struct Heightfield;

struct Keyframe {
  double time = 0;  // seconds, strictly increasing, keyframes at least 1e-6 s apart
  glm::dvec3 eye{0}, target{0};
  double fovDeg = 60;
};

struct CameraPath {
  std::string file;
  std::vector<Keyframe> keys;
  double duration() const { return keys.empty() ? 0.0 : keys.back().time - keys.front().time; }
};

// A sampled camera in world units.
struct CameraPose {
  glm::vec3 eye{0}, target{0};
  float fovDeg = 60;
};

// Throws lb::InputError naming the file, line and column for malformed input.
CameraPath loadCameraPath(const std::string& file);
CameraPath parseCameraPath(const std::string& text, const std::string& nameForErrors);

// Relative keyframe pose at time t (clamped to the path), Catmull-Rom on eye/target, linear fov.
Keyframe interpolate(const CameraPath& path, double t);
// Number of frames when sampling at fps: floor(duration * fps) + 1.
int frameCount(const CameraPath& path, double fps);
// World-space pose of frame i at fps on a terrain (eye kept >= ground + 0.002 * extent), moved by
// the terrain's origin (Heightfield::originX/Z) and rounded to float.
CameraPose samplePose(const CameraPath& path, double fps, int frame, const Heightfield& terrain);
// The pose in terrain-local coordinates (origin subtracted), for CPU metrics that work in them.
CameraPose terrainLocalPose(const CameraPose& pose, const Heightfield& terrain);

}  // namespace lb
