#pragma once
// The stability section of a scenario run (configs/scenarios/*.json, issue 12): the scenario's
// description (the failure it provokes, the seed that predicts it, the metric that shows it) and
// one row per case with that metric, its worst frame and a link to the frame's images.
#include <string>

#include "report/run_data.h"
#include "report/table.h"

namespace lb {

// The config's "description" when the run is a scenario run (config name "scenario-..."), else "".
std::string scenarioDescription(const ReportRun& run);
// The first per-frame metric the description names after "Shows in" (e.g. "err_mean_px"), else "".
std::string scenarioMetric(const std::string& description);
// Per case: mean and max of `metric` over the measured frames, the worst frame, links to its images.
Table scenarioTable(const ReportRun& run, const std::string& metric, const std::string& runHref);

}  // namespace lb
