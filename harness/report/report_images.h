#pragma once
// The report's image strips (one case at one frame, its modes side by side, click to enlarge) and
// the legends of the false-colour modes, whose colours mirror the code that paints them:
// heat map and wireframe: heat() in shaders/terrain.frag; error map: errorImage() in
// harness/replay/measure.cpp; crack mask: crackMaskImage() in harness/metrics/cracks.cpp.
#include <string>
#include <utility>
#include <vector>

#include "report/run_data.h"

namespace lb {

// One row of the image strips: one case at one frame, its images in mode order.
struct Strip {
  const ReportCase* c = nullptr;
  int frame = 0;
  std::vector<std::pair<std::string, std::string>> images;  // mode, path relative to the run dir
};

// Strips for the chosen frames (empty: every frame with images) plus each case's worst frames
// (summary worst_frames, and the frame where scenarioMetric is worst when it is not "").
std::vector<Strip> imageStrips(const ReportRun& run, const std::vector<int>& frames, const std::string& scenarioMetric,
                               std::vector<std::string>& notes);

// The Images section: legends, then the strips; Markdown and HTML.
std::pair<std::string, std::string> imageSection(const ReportRun& run, const std::vector<Strip>& strips,
                                                 const std::string& runHref);

// Width and height from a PNG's header; {0, 0} when the file is missing or not a PNG.
std::pair<int, int> pngSize(const std::string& file);
// An <img> linking a run image (runHref + "/" + file, file relative to the run directory), lazily
// loaded, with its pixel size when the file can be read.
std::string imageTag(const ReportRun& run, const std::string& runHref, const std::string& file, const std::string& alt);

// terrain.frag's heat(): tessellation level -> "#rrggbb" (log2 scale, 1 blue .. 8 green .. 64 red),
// before lighting (the heat map multiplies it by 0.25 + 0.75 * diffuse; wireframe lines do not).
std::string heatColour(double level);
// errorImage()'s grey for an error in pixels: sqrt scale, 0 px black, 8 px and more white.
int errorGrey(double px);
// The legend of one image mode ("" for modes without false colours).
std::string legendHtml(const std::string& mode);

}  // namespace lb
