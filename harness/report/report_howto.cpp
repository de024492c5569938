#include "report/report_howto.h"

#include <stdexcept>

#include "report/table.h"

namespace lb {

namespace {

struct Note {
  const char* key;
  const char* term;
  const char* text;
};

const Note kNotes[] = {
    {"gpu", "GPU ms",
     "GPU time of the frame from timestamp queries: median and p95 over timed frames (warm-up excluded). Lower is "
     "better; it ranks schemes on the device of this run only."},
    {"triangles", "triangles",
     "primitives that reached clipping (clip_primitives), off-screen ones included: the device-independent cost."},
    {"error", "error px",
     "screen-space geometric error: per terrain pixel, the vertical distance between the tessellated and the true "
     "surface, projected to pixels; mean and p95 per frame, then the mean over measured frames. Lower is better."},
    {"surplus", "surplus",
     "the scheme's triangles / the triangles errbound needs for the same p95 error on the same frame. Above 1 it "
     "spends more than errbound; below 1 it beat errbound at equal error: a finding, not a bug (errbound bounds the "
     "maximum error with power-of-two levels, so it is not optimal for the p95)."},
    {"popping", "popping",
     "mean (and p99) absolute RGB difference, 0-255, between the frame drawn with the previous frame's LOD and "
     "with the live LOD: the change a viewer sees caused only by LOD changes. 0 = none; frame 0 has no previous "
     "frame. Lags 2 and 3 compare with the LOD of 2 and 3 frames before: a LOD that flickers back and forth pops "
     "at lag 1 but not at lag 2. Lag frames: the longest run of frames whose mean error was more than 10 % off "
     "the error of the LOD settled at that camera, e.g. after a fast move (0 for a LOD of the camera alone)."},
    {"flip", "FLIP",
     "LDR-FLIP (Andersson et al. 2020): the difference a viewer perceives flipping between the frame and the "
     "ray-cast truth at the configured viewing distance, per pixel from 0 (identical) to 1; mean and p95 per "
     "frame, then the mean over measured frames. Lower is better."},
    {"ssim", "SSIM",
     "structural similarity of the shaded frame to the ray-cast ground truth, 1 = identical, lower = visibly "
     "different structure."},
    {"psnr", "PSNR", "peak signal-to-noise ratio against the same ground truth, in dB: higher is closer."},
    {"cracks", "cracks",
     "edges: shared patch edges whose two tessellation factors differ (where a crack can open); pixels: background "
     "showing through where the ground truth has terrain. Anything above 0 is a watertightness defect."},
    {"saturated", "saturated frames",
     "share of measured frames where a visible patch hit the maximum factor 64: the scheme wanted more detail than "
     "the tessellator gives."},
};

}  // namespace

std::pair<std::string, std::string> howToRead(const std::vector<std::string>& keys) {
  std::string md = "How to read this:",
              html = "<aside class=\"howto\"><div class=\"howto-title\">How to read this</div>";
  for (const std::string& key : keys) {
    const Note* note = nullptr;
    for (const Note& n : kNotes)
      if (key == n.key) note = &n;
    if (!note) throw std::invalid_argument("howToRead: no note for metric '" + key + "'");
    md += std::string(" **") + note->term + "**: " + note->text;
    html += std::string("<div><b>") + htmlEscape(note->term) + ":</b> " + htmlEscape(note->text) + "</div>";
  }
  const std::string link = std::string("[definitions](") + kFormatDocName + ")";
  md += " Full definitions: " + link + ".\n\n";
  html += std::string("<div>Full definitions: <a href=\"") + kFormatDocName + "\">" + kFormatDocName +
          "</a> (docs/results-format.md of this lodbench version).</div></aside>\n";
  return {md, html};
}

}  // namespace lb
