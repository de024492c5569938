#pragma once
// Camera paths: CSV keyframes (time, eye xyz, target xyz, vertical fov in degrees), sampled at a
// fixed frame rate with Catmull-Rom interpolation. Coordinates are relative to the terrain:
// x and z are fractions of the extent ([0,1] covers the terrain), y is in units of the extent
// above the terrain's minimum height. The sampler keeps the eye above the ground.
//
// Scale-free columns (docs/design.md, Camera paths): a header may give a height above the ground
// instead of y, in units of the extent (eye_agl, target_agl) or in sample spacings (eye_agl_sp,
// target_agl_sp), measured from the ground under the eye for both (so equal eye and target values
// look level), and may move x and z by a number of sample spacings (eye_dx_sp, eye_dz_sp,
// target_dx_sp, target_dz_sp). The relative values are interpolated; the ground is looked up per
// sampled frame. An eye given above the ground stays >= kMinEyeAglSpacings spacings above it.
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lb {

struct Heightfield;

// What a keyframe's y means; the header's column picks it, for the eye and the target apart.
enum class PathHeight {
  AboveLowest,          // eye_y / target_y: units of the extent above the terrain's lowest point
  AboveGround,          // eye_agl / target_agl: units of the extent above the ground under the eye
  SpacingsAboveGround,  // eye_agl_sp / target_agl_sp: sample spacings above the ground under the eye
};

// The eye's least height above the ground under it, in sample spacings, when its height is given
// above the ground (eye_agl, eye_agl_sp): within one spacing of the eye the bilinear surface rises
// at most one spacing on slopes up to 45 degrees. Paths with eye_y keep 0.002 x extent.
constexpr double kMinEyeAglSpacings = 1.0;

struct Keyframe {
  double time = 0;               // seconds, strictly increasing, keyframes at least 1e-6 s apart
  glm::dvec3 eye{0}, target{0};  // y in the unit of CameraPath::eyeHeight / targetHeight
  // Sample spacings added to x (.x) and z (.z); .y is unused (0). Zero without *_dx_sp / *_dz_sp.
  glm::dvec3 eyeStepSp{0}, targetStepSp{0};
  double fovDeg = 60;
};

struct CameraPath {
  std::string file;
  std::vector<Keyframe> keys;
  PathHeight eyeHeight = PathHeight::AboveLowest, targetHeight = PathHeight::AboveLowest;
  bool spacingSteps = false;  // a *_dx_sp or *_dz_sp column is present
  double duration() const { return keys.empty() ? 0.0 : keys.back().time - keys.front().time; }
  // Every coordinate relative to the extent and the lowest point (the original format): sampled
  // exactly as before the scale-free columns.
  bool extentOnly() const {
    return eyeHeight == PathHeight::AboveLowest && targetHeight == PathHeight::AboveLowest && !spacingSteps;
  }
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
// World-space pose of frame i at fps on a terrain, moved by the terrain's origin
// (Heightfield::originX/Z) and rounded to float. The eye is kept >= ground + 0.002 * extent (eye_y)
// or >= ground + kMinEyeAglSpacings sample spacings (eye_agl, eye_agl_sp).
CameraPose samplePose(const CameraPath& path, double fps, int frame, const Heightfield& terrain);
// The sample spacing the *_sp columns count in: extent / (samples - 1) along the longer side (the
// finer spacing of a non-square grid).
double sampleSpacing(const Heightfield& terrain);
// The pose in terrain-local coordinates (origin subtracted), for CPU metrics that work in them.
CameraPose terrainLocalPose(const CameraPose& pose, const Heightfield& terrain);

}  // namespace lb
