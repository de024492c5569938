#include "render/instanced.h"

namespace lb {

glm::dvec2 latticeCell(float extent, int width, int height, double cellsPerTexel) {
  return {double(extent) / (double(width - 1) * cellsPerTexel), double(extent) / (double(height - 1) * cellsPerTexel)};
}

}  // namespace lb
