#include "terrain/normal_page_layout.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "shaders/footprint.h"
#include "terrain/normal_map.h"

namespace lb {
namespace {

int pagesAlong(int size, int cells) {
  return size <= 1 ? 1 : (size - 2) / cells + 1;
}

NormalPageLayout layoutOf(int width, int height, int cells) {
  NormalPageLayout l;
  l.cells = cells;
  int w = width, h = height, first = 0;
  const int levels = normalMapLevels(width, height);
  for (int k = 0; k < levels; ++k) {
    NormalPageLevel v{w, h, pagesAlong(w, cells), pagesAlong(h, cells), first};
    first += v.pagesX * v.pagesZ;
    l.levels.push_back(v);
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
  }
  return l;
}

}  // namespace

NormalPageLayout normalPageLayout(int width, int height, int cells,
                                  const std::function<uint64_t(uint64_t pageBytes)>& maxPages) {
  if (width < 1 || height < 1) throw std::invalid_argument("normal map without texels");
  if (cells > 0) return layoutOf(width, height, cells);
  NormalPageLayout best;
  uint64_t bestTexels = UINT64_MAX;
  for (int n = 64; n <= 1024; n *= 2) {
    NormalPageLayout l = layoutOf(width, height, n);
    const uint64_t texels = uint64_t(l.pageCount()) * l.pageTexels();
    const bool fits = !maxPages || uint64_t(l.pageCount()) <= maxPages(l.pageBytes());
    if (fits && texels <= bestTexels) best = std::move(l), bestTexels = texels;
  }
  return best.levels.empty() ? layoutOf(width, height, 1024) : best;  // nothing fits: the caller says so
}

void copyNormalPage(const NormalMap& nm, const NormalPageLayout& layout, int page, uint16_t* out) {
  int k = int(layout.levels.size()) - 1;
  while (k > 0 && layout.levels[size_t(k)].first > page) --k;
  const NormalPageLevel& v = layout.levels[size_t(k)];
  const int local = page - v.first, i = local % v.pagesX, j = local / v.pagesX;
  const auto& texels = nm.levelTexels(k);
  const int n = layout.cells, stored = n + 1;
  for (int z = 0; z < stored; ++z) {
    const int sz = std::min(j * n + z, v.height - 1);
    const uint16_t* row = &texels[size_t(sz) * size_t(v.width) * 2];
    uint16_t* dst = out + size_t(z) * size_t(stored) * 2;
    const int inside = std::max(0, std::min(stored, v.width - i * n));
    std::memcpy(dst, row + size_t(i * n) * 2, size_t(inside) * 4);
    for (int x = inside; x < stored; ++x) {
      dst[2 * x] = row[size_t(v.width - 1) * 2];
      dst[2 * x + 1] = row[size_t(v.width - 1) * 2 + 1];
    }
  }
}

}  // namespace lb
