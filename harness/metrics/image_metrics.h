#pragma once
// Image comparisons on RGBA8 frames (docs/design.md, What is measured): PSNR, SSIM, differing pixels, cracks.
#include <cstdint>
#include <vector>

namespace lb {

struct RgbaImage {
  int width = 0, height = 0;
  std::vector<uint8_t> px;  // width * height * 4
};

struct ImageError {
  double psnrDb = 0;        // over RGB; kPsnrIdentical when the images are identical
  double ssim = 0;          // mean SSIM of luma, 11x11 Gaussian window (sigma 1.5), Wang et al. 2004
  double meanAbsDiff = 0;   // mean over pixels of the mean absolute RGB difference, in 0..255
  double fractionOver = 0;  // fraction of pixels whose largest channel difference exceeds the threshold
  double p99AbsDiff = 0;    // 99th percentile of the per-pixel largest channel difference
  long changedPixels = 0;   // pixels with any channel difference
};
constexpr double kPsnrIdentical = 100.0;

ImageError compareImages(const RgbaImage& a, const RgbaImage& b, int threshold = 16);
double ssim(const RgbaImage& a, const RgbaImage& b);
// SSIM's constants, read by ssim() and by the GPU pass (metrics/gpu_reduce.h) alike.
struct SsimConstants {
  double window[11];  // the normalised Gaussian (sigma 1.5), one axis of the separable window
  double luma[3];     // Rec. 601 weights of R, G, B
  double c1, c2;      // (0.01 x 255)^2, (0.03 x 255)^2
};
const SsimConstants& ssimConstants();

// The clear colour (magenta) marks pixels no terrain covers.
bool isClear(const RgbaImage& img, int x, int y);

// Crack pixels: clear colour in `img` where the crack-free `reference` shows terrain, and the
// pixel is enclosed by terrain of `img` within `reach` pixels on both sides horizontally or
// vertically, and its clear region of `img` (8-connected) touches no pixel the reference shows as
// clear too and does not touch the image border (a hole inside the terrain, not a silhouette
// difference: a coarser silhouette's notch opens onto the sky, however narrow, possibly beyond the
// image border; a crack that reaches the silhouette or the border is missed).
// Returns the count; mask is 0/1 per pixel.
long crackPixels(const RgbaImage& img, const RgbaImage& reference, std::vector<uint8_t>* mask = nullptr, int reach = 3);

}  // namespace lb
