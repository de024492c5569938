#include "replay/popping.h"

#include "metrics/image_metrics.h"
#include "render/renderer.h"
#include "replay/measure_gpu.h"

namespace lb {

PopResult measurePopping(Renderer& renderer, const CameraPose& previous, const CameraPose& current, MeasureGpu* gpu) {
  struct RestoreCulling {  // also when a render throws
    Renderer& r;
    Renderer::CullCamera saved;
    ~RestoreCulling() { r.setCullCamera(saved); }
  } restore{renderer, renderer.cullCamera()};
  renderer.setCullCamera(Renderer::CullCamera::View);
  if (gpu) {
    renderer.renderInto(current, previous, RenderMode::Shaded, &gpu->popFrozen);
    renderer.renderInto(current, current, RenderMode::Shaded, &gpu->popLive);
    ImageError e = gpu->reduce.compare(gpu->popFrozen, gpu->popLive, 16, /*ssim=*/false).e;
    return {e.meanAbsDiff, e.p99AbsDiff, e.changedPixels};
  }
  const int w = renderer.settings().width, h = renderer.settings().height;
  RgbaImage frozen{w, h, renderer.renderImage(current, previous, RenderMode::Shaded)};
  RgbaImage live{w, h, renderer.renderImage(current, current, RenderMode::Shaded)};
  ImageError e = compareImages(frozen, live);
  return {e.meanAbsDiff, e.p99AbsDiff, e.changedPixels};
}

}  // namespace lb
