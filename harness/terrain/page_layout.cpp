#include "terrain/page_layout.h"

#include <algorithm>
#include <cstring>

#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

PageLayout pageLayout(int width, int height, int page) {
  PageLayout l;
  l.samplesX = width;
  l.samplesZ = height;
  // At least one cell a side, so a one-sample axis still has a cell (its border repeats the edge).
  const int cellsX = std::max(width - 1, 1), cellsZ = std::max(height - 1, 1);
  l.cellsX = page > 0 ? std::min(page, cellsX) : cellsX;
  l.cellsZ = page > 0 ? std::min(page, cellsZ) : cellsZ;
  l.pagesX = (cellsX + l.cellsX - 1) / l.cellsX;
  l.pagesZ = (cellsZ + l.cellsZ - 1) / l.cellsZ;
  return l;
}

PageLayout pageLayout(const Heightfield& hf) {
  return pageLayout(hf.width, hf.height, hf.page);
}

void copyPage(const Heightfield& hf, const PageLayout& l, int i, int j, float* out) {
  const int x0 = i * l.cellsX, z0 = j * l.cellsZ;
  for (int z = 0; z < l.storedZ(); ++z) {
    const int sz = std::min(z0 + z, hf.height - 1);
    const float* row = hf.h.data() + size_t(sz) * size_t(hf.width);
    float* dst = out + size_t(z) * size_t(l.storedX());
    const int inside = std::max(0, std::min(l.storedX(), hf.width - x0));
    std::memcpy(dst, row + x0, size_t(inside) * sizeof(float));
    for (int x = inside; x < l.storedX(); ++x) dst[x] = row[hf.width - 1];
  }
}

UninitVector<float> pagedHeights(const Heightfield& hf, const PageLayout& l) {
  if (l.pageCount() == 1 && l.storedX() == hf.width && l.storedZ() == hf.height) return hf.h;
  UninitVector<float> out(l.pageSamples() * size_t(l.pageCount()));
  parallelRows(
      l.pageCount(),
      [&](int p0, int p1) {
        for (int p = p0; p < p1; ++p)
          copyPage(hf, l, p % l.pagesX, p / l.pagesX, out.data() + size_t(p) * l.pageSamples());
      },
      1);
  return out;
}

}  // namespace lb
