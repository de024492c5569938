#pragma once
// LDR-FLIP, the perceived difference of two images flipped back and forth (Andersson, Nilsson,
// Akenine-Moeller, Oskarsson, Astrom, Fairchild: "FLIP: A Difference Evaluator for Alternating
// Images", HPG 2020), written from the paper: a colour pipeline (sRGB to the opponent space YCxCz,
// contrast-sensitivity filters at the viewing distance in pixels per degree, back to linear RGB, then
// Hunt-adjusted L*a*b* and the HyAB distance, compressed so that small differences stay small) and a
// feature pipeline (edge and point detectors on the achromatic channel), combined per pixel as
// colour^(1 - feature). Values lie in [0, 1]. This is the CPU oracle; the GPU pass
// (metrics/gpu_flip.h) computes the same map from the same kernels (flipKernels).
#include <vector>

#include "metrics/image_metrics.h"
#include "shaders/flip_params.h"

namespace lb {

// The paper's viewing condition (shaders/flip_params.h).
constexpr double kFlipDefaultPpd = LB_FLIP_DEFAULT_PPD;

// The filters of one viewing distance, as 1D kernels (every filter of the paper is separable or a
// sum of separable ones), each of 2 r + 1 taps, index r the centre.
struct FlipKernels {
  double ppd = kFlipDefaultPpd;
  int csfRadius = 0;                    // the contrast-sensitivity filters' radius (one for all channels)
  std::vector<double> achromatic;       // Y: one Gaussian, sum 1
  std::vector<double> redGreen;         // Cx: one Gaussian, sum 1
  std::vector<double> blueYellow[2];    // Cz: the sum of two Gaussians, each sum 1, weighted below
  double blueYellowWeight[2] = {0, 0};  // their shares of the 2D kernel's sum (add up to 1)
  int featureRadius = 0;
  std::vector<double> gauss;  // the detectors' smoothing across their direction, sum 1
  std::vector<double> edge;   // first derivative of the Gaussian: positive taps sum 1, negative -1
  std::vector<double> point;  // second derivative of the Gaussian: positive taps sum 1, negative -1
  double cmax = 0;            // the largest colour difference (green against blue) ^ qc
};
FlipKernels flipKernels(double ppd);

// The paper's constants: colour exponent qc, feature exponent qf, and the compression of colour
// differences below pc x cmax onto [0, pt].
constexpr double kFlipQc = 0.7, kFlipQf = 0.5, kFlipPc = 0.4, kFlipPt = 0.95;

// Per-pixel FLIP of `test` against `reference` (RGBA8, sRGB; alpha ignored), row-major, in [0, 1].
// Borders repeat the edge pixel. Throws std::invalid_argument on images of different sizes.
std::vector<float> flipMap(const RgbaImage& reference, const RgbaImage& test, double ppd = kFlipDefaultPpd);

struct FlipStats {
  double mean = 0;  // the paper's authors recommend the mean as the one number (over the weighted median)
  double p95 = 0;   // 95th percentile over pixels
};
FlipStats flipStats(const std::vector<float>& map);

// What a viewer sees of a measurement frame: the clear colour (no terrain) shown as the sky of images
// for people (kSkyRgba), so a silhouette difference is priced against the sky, not against magenta.
RgbaImage asSeen(const RgbaImage& frame);

// The FLIP map for people: 0 black, through purple and orange, 1 pale yellow.
RgbaImage flipImage(const std::vector<float>& map, int width, int height);

}  // namespace lb
