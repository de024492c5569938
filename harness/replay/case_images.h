#pragma once
// The images of a case that people look at: the configured frames and the case's worst
// measured frames (summary worst_frames), in every configured mode, at images.resolution with a
// neutral sky behind the terrain. A second renderer draws them after every timed and measured
// frame, so they cannot perturb the timings; it decides the LOD for the case's own resolution
// (RenderSettings::lodWidth), so each image shows exactly the tessellation the case measured, with
// more pixels. The LOD decision is a pure function of the pose (schemes keep no per-frame state:
// Scheme::update is const), so a frame drawn again from its path pose is the frame measured.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "camera/camera_path.h"
#include "config/config.h"
#include "replay/measure.h"

namespace lb {

struct Context;

// images.resolution fitted to a case's aspect ratio: the smallest size of that aspect ratio that
// covers it (exactly images.resolution when the aspect ratios agree).
std::pair<int, int> imageSize(int caseWidth, int caseHeight, const ImageRequest& request);

// Frames to draw: the configured frames (negative ones count from the end), then, with
// images.worst, every frame the case summary's worst_frames names; each once, in that order.
std::vector<int> imageFrames(const ImageRequest& request, int frames, const nlohmann::json& worstFrames);

struct CaseImageInputs {
  Context& ctx;
  const Case& c;
  const Config& config;
  const Scheme& scheme;
  Renderer& renderer;  // the case's own: its parameters, and crack masks measured at its resolution
  const Heightfield& terrain;
  std::string terrainKey;  // ReferenceCache key of the terrain (run_case.cpp referenceKey)
  ReferenceCache& refs;
  std::function<CameraPose(int)> pose;
  std::string imageDir;
  // Stateful LOD (replay/lod_replay.h): the timed frames' instance counts the replays must meet.
  std::vector<uint32_t> timedLod;
};

// Writes <imageDir>/<case>_f<frame>_<mode>.png for every frame and configured mode and returns
// "images/<name>" for each, in order. `kept`: measured frames whose crack masks are at hand (others
// are measured again). Wireframe images are left out on a device without fillModeNonSolid.
std::vector<std::string> writeCaseImages(const CaseImageInputs& in, const std::vector<int>& frames,
                                         const std::map<int, FrameMetrics>& kept);

}  // namespace lb
