#pragma once
// Image and error-map statistics reduced on the GPU (shaders/reduce_*.comp): a measured frame reads
// back numbers (under 100 KB a call at 1920x1080), not images. Every count and integer sum equals
// the CPU's (compareImages, summarize) exactly; SSIM, the error mean and p95 within the tolerances
// below. A call records, submits and waits for its own command buffer.
#include <functional>
#include <vector>

#include "metrics/image_metrics.h"
#include "render/gpu_profiler.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct ReducePush;  // shaders/reduce_params.h

struct GpuImageStats {
  // As compareImages computes it: PSNR, MAD, fraction over, p99 and changed exactly equal (the
  // sums are exact 64-bit integers, p99 comes from the 256-bin histogram of the largest channel
  // difference); SSIM within 1e-4 (double where the device has shaderFloat64: ~1e-12; float
  // otherwise); NaN when compare() is asked for no SSIM.
  ImageError e;
  long coverageMissing = 0;  // pixels clear (isClear) in `a` where `b` is not clear
  long coverageExtra = 0;    // pixels not clear in `a` where `b` is clear
  long truthTerrain = 0;     // pixels not clear in `b` (coverage's denominator)
  // Pixels clear in `a`, not clear in `b`, and enclosed by a's terrain within `reach` on both sides
  // horizontally or vertically: crackPixels' local conditions (not its background flood fill). 0
  // proves crackPixels(a, b) == 0, so a caller reads images back only when it is > 0.
  long crackCandidates = 0;
};

// Over the values >= 0 (-1 marks a pixel without terrain); NaN when count == 0. count and max are
// exact; mean within 1e-6 relative (float sums of 1024 values, added in double); p95 within 2^-10
// relative (a histogram of the float bits keeping 10 mantissa bits, interpolated inside the bin).
struct GpuErrorStats {
  long count = 0;
  double mean = 0, p95 = 0, max = 0;
};

class GpuReduce {  // one per Context and resolution; holds pipelines and small result buffers
 public:
  // allowFloat64 = false: SSIM in float even where the device has shaderFloat64 (for tests).
  GpuReduce(Context& ctx, int width, int height, bool allowFloat64 = true);

  // a, b: width*height RGBA8 pixels (bytes R,G,B,A, as RgbaImage::px) in device buffers with
  // STORAGE usage, written by work submitted before the call.
  GpuImageStats compare(const Buffer& a, const Buffer& b, int threshold = 16, bool ssim = true, int reach = 3);
  GpuErrorStats errorStats(const Buffer& error);  // width*height floats
  // For tests and callers with host images: a device buffer holding the data (STORAGE | TRANSFER_DST).
  Buffer upload(const RgbaImage& img);
  Buffer upload(const std::vector<float>& v);
  double lastGpuMs() const { return lastGpuMs_; }  // GPU time of the last call (timestamps); NaN without
  bool float64() const { return float64_; }        // SSIM computed in double

 private:
  void bind(const Buffer& a, const Buffer& b);
  // Clears the result words, records `passes` between two timestamps, copies back the header and
  // histograms and `partialWords` partial words into words_, and waits.
  void run(uint32_t partialWords, const std::function<void(VkCommandBuffer)>& passes);
  void dispatch(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t x, uint32_t y, const ReducePush& push);

  Context& ctx_;
  int width_, height_;
  bool float64_ = false;
  double lastGpuMs_ = 0;
  uint32_t imageGroups_ = 0, errorGroups_ = 0, ssimGroupsX_ = 0, ssimGroupsY_ = 0;
  Bindings bindings_;
  vk::Unique<VkPipeline> image_, ssim_, error_, select_, fine_;
  Buffer result_, readback_, weights_;
  PassTimer timer_;
  vk::Unique<VkFence> fence_;
  vk::Unique<VkCommandPool> pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;  // released with pool_
  std::vector<uint32_t> words_;           // the last call's result words as read back
};

}  // namespace lb
