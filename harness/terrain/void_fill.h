#pragma once
// The void fill of the heightmap loaders (internal to harness/terrain): the .hgt loader fills
// SRTM voids and the GDAL loader nodata samples with it, so one DEM read either way gives the
// same bits.
#include <vector>

#include "uninit_vector.h"

namespace lb {

// Fills the samples with known[i] == 0 breadth-first from the known ones inwards: each ring takes
// the mean of its already-known 4-neighbours. Needs at least one known sample; sets known to 1.
void fillVoids(UninitVector<float>& h, std::vector<char>& known, int w, int ht);

}  // namespace lb
