#pragma once
// The report's text, in two renderings of one outline: report.md and the HTML body that
// report/render.mjs wraps (with the chart libraries and embedded images) into report.html.
#include <string>
#include <vector>

#include "report/charts.h"
#include "report/report_images.h"
#include "report/run_data.h"

namespace lb {

struct Page {
  std::string markdown, html;
};

// runHref: the run directory relative to the report directory (links to images in Markdown).
Page buildPage(const ReportRun& run, const std::vector<Chart>& charts, const std::vector<Strip>& strips,
               const std::string& runHref, const std::vector<std::string>& notes);

}  // namespace lb
