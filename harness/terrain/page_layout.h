#pragma once
// How a heightfield is cut into pages on the device (docs/tiled-heightfield.md): page (i, j) stores
// the samples [i cellsX, i cellsX + cellsX] x [j cellsZ, j cellsZ + cellsZ], its cells and a shared
// border row and column on the +x and +z sides, so the four corners of any cell lie in one page.
// The single image is the one-page case (cellsX = width - 1, cellsZ = height - 1). The renderer's
// page arrays and table (render/height_pages.h), the GPU ray cast's heights and the GLSL sampling
// function (shaders/heights.glsl) all use this layout; Heightfield::at and sample read the same
// samples from the host array.
#include <cstddef>
#include <vector>

#include "uninit_vector.h"

namespace lb {

struct Heightfield;

struct PageLayout {
  int samplesX = 0, samplesZ = 0;  // the terrain's samples
  int cellsX = 1, cellsZ = 1;      // cells a page holds along x and z (P); stored sides are one more
  int pagesX = 1, pagesZ = 1;      // ceil((samples - 1) / cells)
  int storedX() const { return cellsX + 1; }
  int storedZ() const { return cellsZ + 1; }
  int pageCount() const { return pagesX * pagesZ; }
  size_t pageSamples() const { return size_t(storedX()) * size_t(storedZ()); }
  // The page holding cell c (and, for c = samples - 1, the last sample) along one axis.
  int pageOfX(int x) const { return x / cellsX < pagesX - 1 ? x / cellsX : pagesX - 1; }
  int pageOfZ(int z) const { return z / cellsZ < pagesZ - 1 ? z / cellsZ : pagesZ - 1; }
};

// Testing only: defects the exactness test (tests/test_tiled_heightfield.cpp) must see, planted by
// the renderer's upload (render/height_pages.h). Pages after the first of a row start one sample too
// far along x; every page's +x border repeats its own last column instead of the next page's first;
// the middle page's table entry points at page 0's layer.
enum class PageDefect { None, OriginOffByOne, BorderLeftOut, WrongLayer };

// page 0: one page (today's single image); otherwise pages of page x page cells, fewer along an axis
// the terrain is shorter than a page.
PageLayout pageLayout(int width, int height, int page);
PageLayout pageLayout(const Heightfield& hf);  // hf.page
// Page (i, j)'s stored samples, row-major, storedX x storedZ floats: the heights' exact bits, and
// past the terrain's +x or +z edge (the last page of a row or column) the edge sample repeated.
void copyPage(const Heightfield& hf, const PageLayout& layout, int i, int j, float* out);
// Every page, page-major (row-major over pages, each as copyPage): the GPU ray cast's heights. For
// the one-page case this equals the host array.
UninitVector<float> pagedHeights(const Heightfield& hf, const PageLayout& layout);

}  // namespace lb
