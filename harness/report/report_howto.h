#pragma once
// "How to read this": one short note per metric, shown beside the tables that hold it, each
// linking to the definitions in results-format.md (a copy of docs/results-format.md that
// writeReport puts next to report.html, so the link works wherever the report folder goes).
#include <string>
#include <utility>
#include <vector>

namespace lb {

// Markdown and HTML (an <aside class="howto">) for the metrics named by key: "error", "surplus",
// "popping", "ssim", "psnr", "cracks", "saturated", "triangles", "gpu". Unknown keys are an error
// of the caller (std::invalid_argument), never dropped.
std::pair<std::string, std::string> howToRead(const std::vector<std::string>& keys);

// Where the copy of docs/results-format.md goes, relative to the report directory.
constexpr const char* kFormatDocName = "results-format.md";

}  // namespace lb
