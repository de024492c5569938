#pragma once
// The summary of a scenario sweep: `lodbench report OUT` on the folder that
// scripts/run-scenarios.sh fills (one run per configs/scenarios/<name>.json) writes one page with
// the grid of scenarios x schemes, coloured by how badly each scheme fails each scenario, each
// cell linking to the case's row in that scenario's own report.
#include <string>

#include "report/report.h"

namespace lb {

// True when dir is not a run itself but holds runs (subfolders with summary.json or cases/).
bool isRunCollection(const std::string& dir);
// Writes report.md, body.html and manifest.json (no charts) into options.outDir or <dir>/report.
// Throws InputError when no subfolder is a scenario run (config name "scenario-...").
ReportOutput writeScenarioSummary(const ReportOptions& options);

}  // namespace lb
