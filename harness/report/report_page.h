#pragma once
// The report's text, in two renderings of one outline: report.md and the HTML body that
// report/render.mjs wraps (with the chart libraries and embedded images) into report.html.
#include <string>
#include <utility>
#include <vector>

#include "report/charts.h"
#include "report/run_data.h"

namespace lb {

// One row of the image strips: one case at one frame, its images in mode order.
struct Strip {
  const ReportCase* c = nullptr;
  int frame = 0;
  std::vector<std::pair<std::string, std::string>> images;  // mode, path relative to the run dir
};

// Strips for the chosen frames (empty: every frame with images) plus each case's worst frames.
std::vector<Strip> imageStrips(const ReportRun& run, const std::vector<int>& frames, std::vector<std::string>& notes);

struct Page {
  std::string markdown, html;
};

// runHref: the run directory relative to the report directory (links to images in Markdown).
Page buildPage(const ReportRun& run, const std::vector<Chart>& charts, const std::vector<Strip>& strips,
               const std::string& runHref, const std::vector<std::string>& notes);

}  // namespace lb
