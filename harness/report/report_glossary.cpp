#include "report/report_glossary.h"

#include <cctype>

#include "schemes/registry.h"

namespace lb {

namespace {

struct Definition {
  const char* header;
  const char* text;
};

// Timing columns are over the timed frames (every frame of the path at the config's fps, warm-up
// excluded, every repetition); error, image and stability columns over the measured frames (every
// measure.every-th frame). docs/results-format.md has the full definitions.
const Definition kDefinitions[] = {
    {"case", "the case id (scheme, parameters, terrain, path, resolution): the name of its file in cases/."},
    {"scheme", "the LOD scheme (README, Schemes); its colour and marker are the same in every chart."},
    {"parameters", "the scheme's parameter values in this case; \"defaults\" when the config set none."},
    {"path", "the camera path (file stem), with terrain and resolution where the run varies them."},
    {"path / terrain", "the camera path and terrain of the case."},
    {"status", "ok; failed (an error stopped the case); skipped (not run, e.g. the device lacks a feature)."},
    {"reason", "why the case failed or was skipped, as its case file records it."},
    {"item", "what the row describes."},
    {"value", "its value for this run."},
    {"frames", "timed frames of the case: the path's frames at the config's fps after warm-up, all repetitions."},
    {"GPU ms median",
     "GPU time of a frame in milliseconds, from Vulkan timestamp queries at the start and end of its "
     "command buffer: median over the timed frames. Lower is faster; it ranks schemes on this "
     "run's device only."},
    {"GPU ms p95", "the same GPU time, 95th percentile over the timed frames: the slow frames."},
    {"GPU ms depth", "median GPU time of the same frames replayed depth-only (no colour, no fragment shader)."},
    {"GPU ms frontend",
     "median GPU time of the same frames replayed with every primitive discarded before "
     "rasterization: vertex work, LOD decision and tessellator only."},
    {"LOD GPU ms",
     "instanced and GPU-indirect paths: median GPU time of the LOD work (compute passes; about 0 "
     "where selection runs on the CPU)."},
    {"draw GPU ms",
     "instanced and GPU-indirect paths: median GPU time of the draws (LOD GPU ms + draw GPU ms = "
     "GPU ms)."},
    {"LOD CPU ms",
     "instanced path: median CPU time of the LOD selection and the upload of its instance records "
     "(part of harness CPU ms, never of GPU ms)."},
    {"CPU ms median",
     "the frame period on the host in milliseconds: median time from one frame's start to the "
     "next (submission, GPU work and the wait for it), over the timed frames."},
    {"harness CPU ms",
     "median host time the harness itself spends per frame (uniforms, command recording, submit, "
     "reading back queries), without waiting for the GPU."},
    {"calibration drift",
     "change of a fixed calibration workload's GPU time from before to after the case, as a "
     "fraction; beyond 2% the clock moved during the case and its times are flagged."},
    {"energy J/frame",
     "joules per frame from the board's energy counter (NVML's total energy; NVIDIA only): the counter's "
     "difference over a window of whole counter ticks of at least 2 s with the path looped, divided by the "
     "frames drawn in it; the mean of 3 such rounds. \"–\" where the board has no counter (the case's "
     "energy_reason says why)."},
    {"energy spread",
     "(max - min) / mean of the energy rounds: the run-to-run spread of the counter, whose sensor samples only "
     "part of each window on some boards; two schemes whose rounds overlap are not ranked on energy."},
    {"FPS median",
     "1000 / GPU ms median: frames per second if the GPU time alone set the pace (not a measured "
     "display rate)."},
    {"triangles median",
     "primitives that reached clipping per frame (clip_primitives), off-screen ones included: "
     "median over the timed frames; it does not depend on the device."},
    {"patches median", "tessellation patches drawn per frame (median); 0 on instanced paths."},
    {"instances median", "instanced paths: drawn grid-block instances per frame (median)."},
    {"degenerate triangles", "triangles of zero area on the ground plane, summed over the measured frames."},
    {"error mean px",
     "screen-space geometric error in pixels: per terrain pixel, the vertical distance between "
     "the drawn and the true surface projected to the screen; the frame's mean, then the mean over "
     "measured frames."},
    {"error p95 px",
     "the same error, the frame's 95th percentile over terrain pixels, then the mean over measured "
     "frames."},
    {"PSNR dB",
     "peak signal-to-noise ratio of the shaded frame against the ray-cast truth, in dB (higher is "
     "closer): mean over measured frames."},
    {"SSIM",
     "structural similarity of the shaded frame to the ray-cast truth (1 = identical): mean over measured "
     "frames."},
    {"FLIP mean",
     "LDR-FLIP of the frame against the ray-cast truth (0 identical .. 1), both seen with the sky where there is "
     "no terrain, at measure.flip_ppd pixels per degree: the mean over pixels, then over measured frames."},
    {"FLIP p95", "the 95th percentile of a frame's FLIP over pixels: mean over measured frames."},
    {"cracks px max",
     "pixels where the background shows through although the truth has terrain: the largest "
     "count over measured frames (0 = watertight)."},
    {"missing terrain px max",
     "pixels where the ray-cast truth shows terrain and the scheme drew none (culled or clipped terrain, coarse "
     "silhouettes, holes): the largest count over measured frames. Error statistics cover drawn pixels only, "
     "so a frame missing more than 10% of the truth's terrain fails the case (Failed and skipped cases)."},
    {"extra terrain px max",
     "pixels where the scheme drew terrain and the ray-cast truth shows none: the largest count over measured "
     "frames."},
    {"popping mean",
     "mean absolute RGB difference (0-255) between the frame drawn with the previous frame's LOD "
     "and with its own: mean over measured frames."},
    {"popping lag 2",
     "as popping mean, against the LOD of 2 frames before (a LOD flipping between two states every frame pops at "
     "lag 1, not at lag 2): mean over measured frames from frame 2 on."},
    {"popping lag 1 / 2 / 3", "popping mean, popping lag 2 and popping lag 3 of the case (as in Every case)."},
    {"popping lag 3",
     "as popping mean, against the LOD of 3 frames before: mean over measured frames from frame 3 on."},
    {"lag frames",
     "the longest run of consecutive frames (every frame of the path, not only measured ones) whose mean error was "
     "more than 10 % off the error of the LOD settled at that frame's camera: how long the LOD lags a camera move "
     "(0 for a LOD decided from the current camera alone)."},
    {"surplus",
     "triangles / the triangles errbound needs for the same p95 error on the same frame: mean over "
     "measured frames (above 1: more than errbound spends)."},
    {"measured frames", "frames that got the measurement passes (every measure.every-th frame)."},
    {"cases ok / failed / skipped", "the scheme's cases on this path by outcome."},
    {"cracks: edges (max)",
     "shared patch edges whose two tessellation factors differ, the largest count of any "
     "measured frame of any case (where a crack can open)."},
    {"cracks: pixels (max)", "crack pixels (as cracks px max), the largest of the scheme's cases."},
    {"popping: mean (max)", "popping mean (as in Every case), the largest of the scheme's cases."},
    {"popping: p99 (max)",
     "the 99th percentile of the per-pixel popping difference, the largest of any measured "
     "frame and case."},
    {"saturated frames (max)",
     "share of measured frames where a visible patch hit the largest factor, 64; the "
     "largest of the scheme's cases."},
    {"surplus: mean (cases' range)", "surplus (as in Every case), the mean over the scheme's cases and their range."},
    {"worst frames", "links to the images of the frame where cracks, popping, error and missing terrain were worst."},
    {"worst frame", "the measured frame where the case's value of the metric was worst."},
    {"images", "the worst frame's images, when the run wrote them."},
    {"scenario", "the scenario: camera path and terrain (row of the grid)."},
    {"draw path",
     "how the scheme's triangles reach the rasterizer: tessellation, instanced grid (CPU selection), GPU-indirect "
     "(compute passes; tessellated when each instance is a patch). docs/draw-paths.md."},
    {"matched parameter", "the scheme's main parameter at the value the matched search found for the target."},
    {"search reached",
     "the metric the search measured at that value, over its evaluation frames; \"unreachable\" when the target "
     "lies beyond the parameter's range and the search stopped at its bound."},
    {"error p95 px, run median",
     "the 95th-percentile screen-space error of each measured frame of the case, median over those frames."},
    {"non-degenerate share",
     "the share of the triangles drawn on measured frames that have some ground area (the others: morph "
     "collapses, clipmap strips, counted by the histogram pass as hist_degenerate)."},
};

}  // namespace

std::string definitionAnchor(const std::string& header) {
  std::string out = "def-";
  bool dash = false;
  for (unsigned char ch : header) {
    if (std::isalnum(ch)) {
      if (dash && out.size() > 4) out += '-';
      out += char(std::tolower(ch));
      dash = false;
    } else {
      dash = true;
    }
  }
  return out;
}

std::optional<std::string> columnDefinition(const ReportRun& run, const std::string& header) {
  for (const Definition& d : kDefinitions)
    if (header == d.header) return std::string(d.text);
  // Scheme counters: "<scheme>: <label>" (SchemeInfo::counters).
  for (const Scheme* s : allSchemes())
    for (const SchemeCounter& c : s->info().counters)
      if (header == s->info().name + ": " + c.label)
        return "a counter of " + s->info().name + ": measured frames where its " + c.frameKey +
               " was above 0, summed over the scheme's cases on the path.";
  // Scenario tables: "<metric> mean" / "<metric> worst", and one grid column per case label.
  for (const char* suffix : {" mean", " worst"}) {
    const std::string sfx = suffix;
    if (header.size() > sfx.size() && header.compare(header.size() - sfx.size(), sfx.size(), sfx) == 0)
      return "the scenario's metric " + header.substr(0, header.size() - sfx.size()) +
             (sfx == " mean" ? ": its mean over the case's measured frames." : ": its worst measured frame's value.");
  }
  for (const ReportCase& c : run.cases)
    if (header == c.label)
      return "the case " + c.label + ": its value of the grid's metric, as the paragraph above the grid says.";
  return std::nullopt;
}

}  // namespace lb
