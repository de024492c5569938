#pragma once
// Coverage error (docs/results-format.md, "Coverage"): terrain the scheme leaves out of the frame or
// adds to it, against the ray-cast truth. The error map and crack metrics only see pixels the scheme
// draws, and cracks only holes enclosed by terrain, so a scheme that culls visible terrain at the
// border or the horizon (or draws none at all) escapes them; this count does not.
#include "metrics/image_metrics.h"

namespace lb {

struct Coverage {
  long missing = 0;       // clear (isClear) in the scheme's frame where the truth shows terrain
  long extra = 0;         // terrain in the scheme's frame where the truth is clear
  long truthTerrain = 0;  // pixels where the truth shows terrain
};

// Both images the same size (else std::invalid_argument naming both sizes). A GPU reduction of the
// same counts must keep exactly this definition.
Coverage coverageError(const RgbaImage& shaded, const RgbaImage& truth);

// A measured frame fails coverage when the terrain it misses or adds exceeds this fraction of the
// truth's terrain pixels (or any terrain is added where the truth has none). Set from the shipped
// schemes on the shipped paths (docs/results-format.md, "Coverage"): coarse silhouettes near the
// horizon miss a few pixels, a scheme that culls visible terrain misses far more.
constexpr double kCoverageTolerance = 0.10;
bool coverageFailed(const Coverage& c);
bool coverageFailed(double missing, double extra, double truthTerrain);

}  // namespace lb
