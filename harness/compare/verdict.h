#pragma once
// The verdict of lodbench compare as JSON (machine-readable) and Markdown (for people and CI logs).
#include <nlohmann/json.hpp>
#include <string>

#include "compare/compare.h"

namespace lb {

constexpr int kVerdictSchemaVersion = 1;

nlohmann::json verdictJson(const CompareReport& report);
// One line: regression or not, then the largest GPU time ratio with its p and what it means, e.g.
// "no regression (3 cases); GPU time ratio 1.56x (largest, uniform-level8), p = 2.7e-11: slower,
// within the threshold (2x)". Heads the Markdown and the stderr summary.
std::string verdictLine(const CompareReport& report);
// A case's timing verdict in words: a significant change under the threshold is "slower, within
// the threshold (2x)", not "unchanged".
std::string timingWords(const TimingCheck& timing, const CompareOptions& options);
std::string verdictMarkdown(const CompareReport& report);
// Writes either file when its path is non-empty (atomically: temp file + rename).
void writeVerdict(const CompareReport& report, const std::string& jsonPath, const std::string& mdPath);

}  // namespace lb
