#pragma once
// Definitions of every column the report's tables show (CPU ms, harness CPU ms, FPS, ...): the
// page links each table header to its entry in a "Column definitions" section at the end.
#include <optional>
#include <string>

#include "report/run_data.h"

namespace lb {

// What a column means, with its unit and the frames it is taken over; nullopt for a header this
// module does not know (a test keeps every header the report writes defined).
std::optional<std::string> columnDefinition(const ReportRun& run, const std::string& header);
// The in-page anchor of a header's definition: "def-" + the header in lower case, runs of other
// characters as one "-".
std::string definitionAnchor(const std::string& header);

}  // namespace lb
