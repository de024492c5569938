#pragma once
// LDR-FLIP (metrics/flip.h) as compute passes (shaders/flip_rows.comp, flip_cols.comp,
// flip_combine.comp): the truth and the frame stay in device buffers, the FLIP map is written to a
// device buffer that GpuReduce::errorStats reduces to its mean and p95. The same kernels as the CPU
// oracle (flipKernels), summed in the same order, in float: within 1e-4 of the oracle per pixel
// (tests/test_gpu_flip.cpp). A call records, submits and waits.
#include "metrics/flip.h"
#include "vk/resources.h"

namespace lb {

struct Context;

class GpuFlip {  // one per Context, resolution and viewing distance
 public:
  GpuFlip(Context& ctx, int width, int height, double ppd);
  // reference, test: width*height RGBA8 pixels in STORAGE buffers, written by earlier submissions.
  // Writes the map into `map` (this object's buffer) and returns it.
  const Buffer& run(const Buffer& reference, const Buffer& test);
  const Buffer& map() const { return map_; }
  double ppd() const { return ppd_; }

 private:
  Context& ctx_;
  int width_, height_;
  double ppd_;
  FlipKernels kernels_;
  Bindings bindings_;
  vk::Unique<VkPipeline> rows_, cols_, combine_;
  Buffer planes_, kernelBuffer_, map_;
};

}  // namespace lb
