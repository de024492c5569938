#include "replay/popping.h"

#include "metrics/image_metrics.h"
#include "render/renderer.h"
#include "replay/measure_gpu.h"

namespace lb {

PopResult measurePopping(Renderer& renderer, const CameraPose& previous, const CameraPose& current, MeasureGpu* gpu) {
  return measurePopping(renderer, std::vector<CameraPose>{previous}, current, gpu).at(0);
}

std::vector<PopResult> measurePopping(Renderer& renderer, const std::vector<CameraPose>& previous,
                                      const CameraPose& current, MeasureGpu* gpu) {
  struct RestoreCulling {  // also when a render throws
    Renderer& r;
    Renderer::CullCamera saved;
    ~RestoreCulling() { r.setCullCamera(saved); }
  } restore{renderer, renderer.cullCamera()};
  renderer.setCullCamera(Renderer::CullCamera::View);
  std::vector<PopResult> out;
  if (gpu) {
    renderer.renderInto(current, current, RenderMode::Shaded, &gpu->popLive);
    for (const CameraPose& p : previous) {
      renderer.renderInto(current, p, RenderMode::Shaded, &gpu->popFrozen);
      ImageError e = gpu->reduce.compare(gpu->popFrozen, gpu->popLive, 16, /*ssim=*/false).e;
      out.push_back({e.meanAbsDiff, e.p99AbsDiff, e.changedPixels});
    }
    return out;
  }
  const int w = renderer.settings().width, h = renderer.settings().height;
  RgbaImage live{w, h, renderer.renderImage(current, current, RenderMode::Shaded)};
  for (const CameraPose& p : previous) {
    RgbaImage frozen{w, h, renderer.renderImage(current, p, RenderMode::Shaded)};
    ImageError e = compareImages(frozen, live);
    out.push_back({e.meanAbsDiff, e.p99AbsDiff, e.changedPixels});
  }
  return out;
}

}  // namespace lb
