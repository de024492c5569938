#pragma once
// The verdict of lodbench compare as JSON (machine-readable) and Markdown (for people and CI logs).
#include <nlohmann/json.hpp>
#include <string>

#include "compare/compare.h"

namespace lb {

constexpr int kVerdictSchemaVersion = 1;

nlohmann::json verdictJson(const CompareReport& report);
std::string verdictMarkdown(const CompareReport& report);
// Writes either file when its path is non-empty (atomically: temp file + rename).
void writeVerdict(const CompareReport& report, const std::string& jsonPath, const std::string& mdPath);

}  // namespace lb
