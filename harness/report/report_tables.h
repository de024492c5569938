#pragma once
// The report's tables: run context, every case's summary, stability per scheme and path, and the
// cases that failed or were skipped.
#include <string>
#include <vector>

#include "report/run_data.h"
#include "report/table.h"

namespace lb {

// runHref: the run directory as seen from the report directory ("..", or a relative path when
// --out puts the report elsewhere); Markdown links to images go through it.
Table contextTable(const ReportRun& run);
// omitted receives the columns no case has (left out of the table).
Table caseTable(const ReportRun& run, std::vector<std::string>& omitted);
Table stabilityTable(const ReportRun& run, const std::string& runHref);
Table problemTable(const ReportRun& run);

// In-page anchor of one frame's image strip.
std::string imageAnchor(const std::string& caseId, int frame);
// A worst frame the report names but has no image of: the text, and in HTML a span.no-image with
// data-case and data-frame that the browser test counts (report/test).
Cell missingImageCell(const std::string& caseId, int frame);
// Frames the stability table links to (worst cracks, popping, error), for the image strips.
std::vector<int> worstFrames(const ReportCase& c);
// What frame is the worst of for this case ("cracks, error"), or "".
std::string worstOf(const ReportCase& c, int frame);

}  // namespace lb
