#pragma once
// The stability section of a scenario run (configs/scenarios/*.json): the scenario's
// description (the failure it provokes, the seed that predicts it, the metric that shows it), a
// summary grid of scenarios x schemes coloured by how badly each fails, and one row per case with
// that metric, its worst frame and a link to the frame's images.
#include <string>
#include <utility>
#include <vector>

#include "report/run_data.h"
#include "report/table.h"

namespace lb {

// The config's "description" when the run is a scenario run (config name "scenario-..."), else "".
std::string scenarioDescription(const ReportRun& run);
// The first per-frame metric the description names after "Shows in" (e.g. "err_mean_px"), else "".
std::string scenarioMetric(const std::string& description);
// Whether a larger value of the metric is better (PSNR, SSIM), i.e. the grid's best is the largest.
bool higherIsBetter(const std::string& metric);

// The summary grid's rule: badness = |value - best| / |worst - best| over the finished cases of one
// scenario row (0: the best case there, 1: the worst; 0 for all when they are equal).
double badness(double value, double best, double worst);
// How the grid is read (the rule above, in words, with the metric named).
std::string scenarioGridRule(const std::string& metric);
// Rows: the run's scenarios (path / terrain); columns: scheme and parameters in case order. Each cell
// holds the case's mean of `metric` over measured frames, coloured by badness, linking to its row
// of scenarioTable (id scenarioRowId). A case without the metric shows "–" and is not coloured.
Table scenarioGrid(const ReportRun& run, const std::string& metric);
// The grid's parts, for grids over several runs (scenario_summary.h): the columns (scheme and
// parameters, first appearance first), and one run's rows (label, cells); links go to
// <prefix>#scn-<case id> (prefix "" in the same page).
std::vector<std::string> gridColumns(const std::vector<const ReportRun*>& runs);
std::vector<std::pair<std::string, std::vector<Cell>>> gridRows(const ReportRun& run,
                                                                const std::vector<std::string>& columns,
                                                                const std::string& metric, const std::string& mdPrefix,
                                                                const std::string& htmlPrefix);
// The control row of a scenario whose description says it shows in "the difference from the ..."
// case (far-origin): the scenario whose label begins every other one's; "" for other scenarios.
std::string controlScenario(const ReportRun& run);
// What each (non-control) row of the grid shows, in one sentence per row: the worst and the best
// case on `metric`, or, where every case reads the same, that the predicted failure did not appear
// there (a scenario that provokes nothing is reported, not hidden).
std::vector<std::string> scenarioOutcomes(const ReportRun& run, const std::string& metric);
// Per case: mean and max of `metric` over the measured frames, the worst frame, links to its images.
Table scenarioTable(const ReportRun& run, const std::string& metric, const std::string& runHref);
std::string scenarioRowId(const std::string& caseId);
// The frame where the case's `metric` is worst (-1 when no measured frame has it).
int scenarioWorstFrame(const ReportCase& c, const std::string& metric);

}  // namespace lb
