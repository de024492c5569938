#pragma once
// The report's opening answer: which scheme is fastest at a given accuracy and which is
// most accurate at a given cost, in sentences generated from the run's figures, with the threshold
// each uses (chosen from the data and stated) and the caveat of the device the times come from.
#include <string>
#include <vector>

#include "report/run_data.h"

namespace lb {

// One paragraph per scenario (camera path / terrain) of the run, plus the device caveat; when the
// run has no error pass (or no finished case), a paragraph saying what cannot be answered and why.
std::vector<std::string> openingAnswer(const ReportRun& run);

// The median of values (mean of the two middle ones for an even count); values must not be empty.
double medianOf(std::vector<double> values);
// A CPU rasterizer by its recorded device name (llvmpipe, lavapipe, SwiftShader): its timings are
// no verdict on a GPU's, least of all across draw paths.
bool softwareRasterizer(const std::string& device);

}  // namespace lb
