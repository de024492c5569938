#pragma once
// The real DEM every test uses: a 601 x 601 crop of the SRTM tile N44W072 committed under
// tests/data (provenance in tests/data/README.md), so a clone with nothing beside it runs every
// test. Spacing as the full tile was used before (3 arc-seconds ~ 90 m, 600 intervals = 54 km),
// with the vertical exaggeration of 5 that the full-tile sweeps use.
#include <string>

#include "terrain/heightfield.h"

namespace lbtest {

inline lb::TerrainSpec demCrop() {
  lb::TerrainSpec s;
  s.type = "hgt";
  s.file = std::string(LODBENCH_SOURCE_DIR) + "/tests/data/N44W072_crop601.hgt";
  s.extent = 54000;
  s.heightScale = 5;
  return s;
}

}  // namespace lbtest
