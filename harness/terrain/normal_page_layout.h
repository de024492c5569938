#pragma once
// How the normal map's levels are cut into pages on the device (docs/tiled-heightfield.md), so a
// terrain's normal map is bounded by the device's memory, not by one image's side or allocation.
// Every level is cut alike: page (i, j) of level k stores that level's texels [i N, i N + N] x
// [j N, j N + N], N x N of its own and a shared +x/+z border, the texels past the level's edge
// repeating the edge. A bilinear read clamps its two texels a axis to [0, size - 1] and takes them
// from page min(a / N, pages - 1), which holds both, so its four texels are one page's. Pages are
// numbered level after level, row-major in a level; the renderer fills arrays of equal layers in
// that order. Only storage changes: the texels read and the arithmetic on them (shaders/
// normal_sample.glsl) do not depend on N, so a terrain shades alike at any page size.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace lb {

struct NormalMap;

struct NormalPageLevel {
  int width = 0, height = 0;   // the level's texels
  int pagesX = 1, pagesZ = 1;  // max(1, ceil((size - 1) / N)) along each axis
  int first = 0;               // the level's first page in the numbering
};

struct NormalPageLayout {
  int cells = 1;  // N: texels a page holds of its own along each axis; stored sides are N + 1
  std::vector<NormalPageLevel> levels;
  int pageCount() const {
    return levels.empty() ? 0 : levels.back().first + levels.back().pagesX * levels.back().pagesZ;
  }
  size_t pageTexels() const { return size_t(cells + 1) * size_t(cells + 1); }
  uint64_t pageBytes() const { return uint64_t(pageTexels()) * 4; }  // R16G16_SFLOAT
};

// The layout of a width x height terrain's normal map (levels as NormalMap builds them) in pages of
// `cells`; cells 0 chooses it: of 64, 128, ..., 1024, the one storing the fewest texels whose
// pages fit (count <= maxPages(pageBytes), when given; ties go to the larger).
NormalPageLayout normalPageLayout(int width, int height, int cells = 0,
                                  const std::function<uint64_t(uint64_t pageBytes)>& maxPages = {});
// Page `page` (numbered as above) of the map: pageTexels() RG16F texel pairs, row-major.
void copyNormalPage(const NormalMap& nm, const NormalPageLayout& layout, int page, uint16_t* out);

}  // namespace lb
