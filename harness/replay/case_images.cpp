#include "replay/case_images.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "metrics/cracks.h"
#include "metrics/flip.h"
#include "render/image_io.h"
#include "replay/lod_replay.h"
#include "replay/run_case.h"
#include "vk/context.h"

namespace lb {

std::pair<int, int> imageSize(int caseWidth, int caseHeight, const ImageRequest& request) {
  double s = std::max(double(request.width) / caseWidth, double(request.height) / caseHeight);
  auto side = [&](int n) { return std::clamp(int(std::lround(n * s)), 16, 8192); };
  return {side(caseWidth), side(caseHeight)};
}

std::vector<int> imageFrames(const ImageRequest& request, int frames, const nlohmann::json& worstFrames) {
  std::vector<int> out;
  auto add = [&](int f) {
    if (f >= 0 && f < frames && std::find(out.begin(), out.end(), f) == out.end()) out.push_back(f);
  };
  for (int f : request.frames) add(f < 0 ? frames + f : f);
  if (request.worst && worstFrames.is_object()) {
    std::vector<int> worst;
    for (auto& [metric, f] : worstFrames.items())
      if (f.is_number_integer()) worst.push_back(f.get<int>());
    std::sort(worst.begin(), worst.end());
    for (int f : worst) add(f);
  }
  return out;
}

// The measured crack mask of `frame` at the case's resolution (magenta clear colour, ray-cast truth).
static std::vector<uint8_t> crackMask(const CaseImageInputs& in, int frame, const std::map<int, FrameMetrics>& kept) {
  auto k = kept.find(frame);
  if (k != kept.end() && !k->second.crackMask.empty()) return k->second.crackMask;
  MeasureSpec one = in.config.measure;
  one.every = 1;
  one.passes = {"cracks"};
  FrameMetrics m = measureFrame(in.ctx, in.renderer, in.scheme, in.renderer.params(), in.terrain, in.terrainKey, one,
                                in.refs, frame, in.pose(std::max(0, frame - 1)), in.pose(frame));
  return m.crackMask;
}

// The measured FLIP map of `frame` at the case's resolution (metrics/flip.h), as a picture.
static std::vector<uint8_t> flipPicture(const CaseImageInputs& in, int frame, const std::map<int, FrameMetrics>& kept) {
  auto k = kept.find(frame);
  std::vector<float> map;
  if (k != kept.end() && !k->second.flipMap.empty()) {
    map = k->second.flipMap;
  } else {
    MeasureSpec one = in.config.measure;
    one.every = 1;
    one.passes = {"image"};
    map = measureFrame(in.ctx, in.renderer, in.scheme, in.renderer.params(), in.terrain, in.terrainKey, one, in.refs,
                       frame, in.pose(std::max(0, frame - 1)), in.pose(frame), nullptr, /*keepPixels=*/true)
              .flipMap;
  }
  return flipImage(map, in.c.width, in.c.height).px;
}

std::vector<std::string> writeCaseImages(const CaseImageInputs& in, const std::vector<int>& frames,
                                         const std::map<int, FrameMetrics>& kept) {
  std::vector<std::string> written;
  const auto& modes = in.config.images.modes;
  if (frames.empty() || modes.empty()) return written;
  const Case& c = in.c;
  auto [w, h] = imageSize(c.width, c.height, in.config.images);
  RenderSettings rs = in.renderer.settings();
  rs.width = w, rs.height = h;
  rs.lodWidth = c.width, rs.lodHeight = c.height;
  rs.sky = true;
  rs.testSlowdown = 0;
  Renderer img(in.ctx, in.terrain, rs);
  img.setScheme(in.scheme, in.renderer.params());
  // A stateful LOD: both renderers walk from the case's S0 to each frame, drawing frozen there.
  std::unique_ptr<LodReplay> imgReplay, caseReplay;
  std::unique_ptr<FrozenLod> imgFrozen, caseFrozen;
  if (in.renderer.statefulLod()) {
    in.renderer.lodState().restore();
    img.lodState().load(in.renderer.lodState().read());
    img.lodState().snapshot();
    imgReplay = std::make_unique<LodReplay>(img, in.pose, in.timedLod);
    caseReplay = std::make_unique<LodReplay>(in.renderer, in.pose, in.timedLod);
  }
  std::vector<int> ordered = frames;
  if (imgReplay) std::sort(ordered.begin(), ordered.end());  // a replay only moves forward
  for (int frame : ordered) {
    const CameraPose p = in.pose(frame);
    if (imgReplay) {
      imgFrozen.reset();
      caseFrozen.reset();
      imgReplay->advanceTo(frame);
      caseReplay->advanceTo(frame);
      imgFrozen = std::make_unique<FrozenLod>(img);
      caseFrozen = std::make_unique<FrozenLod>(in.renderer);
    }
    std::vector<uint8_t> shaded;  // drawn once per frame when two modes need it
    auto shadedPx = [&]() -> const std::vector<uint8_t>& {
      if (shaded.empty()) shaded = img.renderImage(p, p, RenderMode::Shaded);
      return shaded;
    };
    for (const std::string& mode : modes) {
      std::vector<uint8_t> px;
      if (mode == "error") {
        px = errorImage(img.renderErrorMap(p, p), w, h).px;
      } else if (mode == "cracks") {
        // The crack pixels the case measured at its own resolution, scaled up, over the dimmed frame.
        std::vector<uint8_t> mask = crackMask(in, frame, kept);
        if (mask.empty()) continue;
        px = crackMaskImage({w, h, shadedPx()}, scaleNearest(mask, c.width, c.height, 1, w, h)).px;
      } else if (mode == "flip") {
        // Measured at the case's own resolution (a perceptual error depends on the pixel size), scaled up.
        px = scaleNearest(flipPicture(in, frame, kept), c.width, c.height, 4, w, h);
      } else if (mode == "shaded") {
        px = shadedPx();
      } else {
        RenderMode m = parseRenderMode(mode);
        if (m == RenderMode::Wireframe && !in.ctx.enabledFeatures.fillModeNonSolid) continue;
        px = img.renderImage(p, p, m);
      }
      std::string name = c.id + "_f" + std::to_string(frame) + "_" + mode + ".png";
      writePng(in.imageDir + "/" + name, w, h, px);
      written.push_back("images/" + name);
    }
  }
  return written;
}

}  // namespace lb
