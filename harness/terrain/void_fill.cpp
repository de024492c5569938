// Void fill shared by the .hgt and GDAL loaders (void_fill.h).
#include "terrain/void_fill.h"

#include <cstddef>

namespace lb {

// Fills voids breadth-first from the valid samples inwards: each ring takes the mean of its
// already-known 4-neighbours. Rings are computed from a snapshot so the result does not depend
// on scan order, and the whole fill is O(samples) however large the voids are.
void fillVoids(UninitVector<float>& h, std::vector<char>& known, int w, int ht) {
  std::vector<size_t> frontier, next;
  auto pushVoidNeighbours = [&](size_t i, std::vector<size_t>& out, std::vector<char>& queued) {
    const int x = int(i % size_t(w)), z = int(i / size_t(w));
    const int nx[4] = {x - 1, x + 1, x, x}, nz[4] = {z, z, z - 1, z + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || nx[k] >= w || nz[k] < 0 || nz[k] >= ht) continue;
      const size_t j = size_t(nz[k]) * size_t(w) + size_t(nx[k]);
      if (!known[j] && !queued[j]) {
        queued[j] = 1;
        out.push_back(j);
      }
    }
  };
  std::vector<char> queued(h.size(), 0);
  for (size_t i = 0; i < h.size(); ++i)
    if (known[i]) pushVoidNeighbours(i, frontier, queued);
  std::vector<float> ring;
  while (!frontier.empty()) {
    ring.assign(frontier.size(), 0.0f);
    for (size_t k = 0; k < frontier.size(); ++k) {
      const size_t i = frontier[k];
      const int x = int(i % size_t(w)), z = int(i / size_t(w));
      float sum = 0.0f;
      int count = 0;
      if (x > 0 && known[i - 1]) sum += h[i - 1], ++count;
      if (x + 1 < w && known[i + 1]) sum += h[i + 1], ++count;
      if (z > 0 && known[i - size_t(w)]) sum += h[i - size_t(w)], ++count;
      if (z + 1 < ht && known[i + size_t(w)]) sum += h[i + size_t(w)], ++count;
      ring[k] = sum / float(count);  // count >= 1: frontier cells touch a known cell
    }
    for (size_t k = 0; k < frontier.size(); ++k) h[frontier[k]] = ring[k], known[frontier[k]] = 1;
    next.clear();
    for (size_t i : frontier) pushVoidNeighbours(i, next, queued);
    frontier.swap(next);
  }
}

}  // namespace lb
