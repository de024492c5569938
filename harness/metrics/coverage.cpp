#include "metrics/coverage.h"

#include <stdexcept>
#include <string>

namespace lb {

Coverage coverageError(const RgbaImage& shaded, const RgbaImage& truth) {
  if (shaded.width != truth.width || shaded.height != truth.height)
    throw std::invalid_argument("coverageError: frame " + std::to_string(shaded.width) + "x" +
                                std::to_string(shaded.height) + " against truth " + std::to_string(truth.width) + "x" +
                                std::to_string(truth.height));
  Coverage c;
  for (int y = 0; y < shaded.height; ++y)
    for (int x = 0; x < shaded.width; ++x) {
      const bool drawn = !isClear(shaded, x, y), real = !isClear(truth, x, y);
      c.truthTerrain += real;
      c.missing += real && !drawn;
      c.extra += drawn && !real;
    }
  return c;
}

bool coverageFailed(double missing, double extra, double truthTerrain) {
  const double allowed = kCoverageTolerance * truthTerrain;
  return missing > allowed || extra > allowed;
}

bool coverageFailed(const Coverage& c) {
  return coverageFailed(double(c.missing), double(c.extra), double(c.truthTerrain));
}

}  // namespace lb
