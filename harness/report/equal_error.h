#pragma once
// "Cost at equal error": in a run whose cases were matched to one p95 error (config "match" on
// err_p95_px), every scheme's cost where it reaches that error, whatever its draw path: GPU ms
// (median, p95), energy per frame where the board has a counter (NVML), the LOD and draw split
// where the path has one, triangles and the non-degenerate ones. The question it answers: at the
// same accuracy, which way of making triangles costs least.
#include <string>
#include <vector>

#include "report/charts.h"
#include "report/run_data.h"
#include "report/table.h"

namespace lb {

struct EqualErrorSection {
  bool present = false;  // the run matched its cases to an error
  std::string title;     // "Cost at equal error: p95 error 0.5 px"
  std::string intro;     // what the table holds, and how the match was made
  std::string caveat;    // the device caveat ("" on a hardware GPU)
  // Energy per frame at the target, lowest first, ranked only across the sensor's spread:
  // "cdlod 0.0120 J < sphere 0.0150 J ~ cbt 0.0155 J ..." ("" where no case measured energy).
  std::string energy;
  Table table;  // one row per matched case, cheapest first
  Chart chart;  // GPU ms per scheme at the target, split into LOD and draw where known
};

EqualErrorSection equalErrorSection(const ReportRun& run);

// One scheme's energy per frame: the mean and the range of its rounds (summary energy_j_per_frame).
struct EnergyFigure {
  std::string label;
  double mean = 0, min = 0, max = 0, spread = 0;
};
// Lowest mean first, "<" between two neighbours only where every round before it lies below every
// round after it, else "≈" (their rounds overlap: within the sensor's spread, not ranked on energy).
std::string energyRanking(std::vector<EnergyFigure> figures);

}  // namespace lb
