#include "config/measure_spec.h"

namespace lb {

const std::set<std::string>& allMeasurePasses() {
  static const std::set<std::string> passes = {"histogram", "error", "image", "cracks", "popping", "surplus"};
  return passes;
}

}  // namespace lb
