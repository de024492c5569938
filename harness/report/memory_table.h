#pragma once
// The report's "Memory" section: per case, the device memory its renderer held by resource (the
// capture buffers apart) and the process's peak host memory (summary "memory",
// docs/results-format.md), and the figures the equal-error table shows beside milliseconds.
#include <optional>
#include <string>

#include "report/run_data.h"
#include "report/table.h"

namespace lb {

// One row per finished case with a memory record; empty where no case has one.
Table memoryTable(const ReportRun& run);
// summary.memory.<field> as a number; nullopt where absent or null.
std::optional<double> memoryValue(const ReportCase& c, const char* field);
// Bytes as MiB with 2 decimals ("1.25"), or the report's mark for a missing value.
std::string mibText(const std::optional<double>& bytes);

}  // namespace lb
