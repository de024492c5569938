#pragma once
// "Cost at equal error": in a run whose cases were matched to one p95 error (config "match" on
// err_p95_px), every scheme's cost where it reaches that error, whatever its draw path: GPU ms
// (median, p95), the LOD and draw split where the path has one, triangles and the non-degenerate
// ones. The question it answers: at the same accuracy, which way of making triangles costs least.
#include <string>

#include "report/charts.h"
#include "report/run_data.h"
#include "report/table.h"

namespace lb {

struct EqualErrorSection {
  bool present = false;  // the run matched its cases to an error
  std::string title;     // "Cost at equal error: p95 error 0.5 px"
  std::string intro;     // what the table holds, and how the match was made
  std::string caveat;    // the device caveat ("" on a hardware GPU)
  Table table;           // one row per matched case, cheapest first
  Chart chart;           // GPU ms per scheme at the target, split into LOD and draw where known
};

EqualErrorSection equalErrorSection(const ReportRun& run);

}  // namespace lb
