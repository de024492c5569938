#pragma once
// A non-square terrain for tests: the first rows of a square one, stretched over the same extent.
#include "terrain/heightfield.h"

namespace lbtest {

inline lb::Heightfield cropRows(lb::Heightfield hf, int rows) {
  hf.height = rows;
  hf.h.resize(size_t(hf.width) * size_t(rows));
  hf.updateRange();
  return hf;
}

}  // namespace lbtest
