#pragma once
// The side-by-side view: one frame, every scheme, its shaded, heat-map and error images in a grid
// (one row per scheme), each scheme at the setting whose error on that frame is closest to a common
// target, and a "flip" viewer that toggles one image between two chosen schemes.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report/run_data.h"

namespace lb {

struct SideBySideRow {
  const ReportCase* c = nullptr;
  std::optional<double> error;  // err_mean_px on the frame (or the case's mean); none without an error pass
  bool frameError = false;      // error is the frame's own
  bool matched = false;         // within kMatchFactor of the target; else the scheme's default setting
};

struct SideBySide {
  std::string scenario;  // the path (and terrain) the frame belongs to
  int frame = -1;        // -1: no frame has images of two or more schemes
  double target = 0;
  std::vector<SideBySideRow> rows;  // scheme order
};

// A setting matches when its error lies within this factor of the target, either way.
constexpr double kMatchFactor = 1.5;

// The frame: the one of one path with images of the most schemes (ties: the later frame). The target: the
// median error over every case imaged at that frame. Per scheme: the case closest to the target
// (log ratio) when it matches, else the case at the scheme's default main parameter, else its
// middle setting.
SideBySide chooseSideBySide(const ReportRun& run);

// The section: Markdown and HTML ("" for both when no frame has images of two schemes).
std::pair<std::string, std::string> sideBySideSection(const ReportRun& run, const std::string& runHref);

}  // namespace lb
