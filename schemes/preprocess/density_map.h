#pragma once
// Density map (AMD "Detail Tessellation 11", Density-based Tessellation; Rapp 2011, 5.2.3): how much the
// surface bends at each heightfield sample, from second differences of the heights. Computed once at
// load time; the density and phong schemes scale screen-space tessellation factors by it.
#include <glm/glm.hpp>
#include <vector>

namespace lb {

struct Heightfield;

constexpr float kMinDensity = 1.0f / 255.0f;  // the seed's clamp minimum (one step of its 8-bit map)

// One density per heightfield sample, row-major like Heightfield::h, each in [1/255, 1].
// Heights are first normalised to [0, 1] by the heightfield's range, because the seed's maps are 8-bit
// and its threshold and scale are in that unit. Then per sample (seed Figure 5-8 and the text after it):
// the absolute second differences along x, along z and along both diagonals; each one that is
// >= threshold is added, x and z weighted 0.293, diagonals 0.207; the sum is multiplied by scale and
// clamped to [1/255, 1]. Samples on the border lack neighbours and copy the nearest interior sample
// (a terrain's border is a real silhouette; the SDK sample wrote the minimum there because its maps tile).
std::vector<float> densityMap(const Heightfield& hf, float threshold, float scale);
// Samples x0 .. x0 + count - 1 (inside the terrain) of row z of densityMap, the same floats, into out:
// what the renderer asks for page by page, so that no whole-terrain map exists on the host.
void densityRow(const Heightfield& hf, float threshold, float scale, int z, int x0, int count, float* out);

// Texel of grid vertex index i on an axis of `size` samples divided into n patches:
// round(i * (size - 1) / n), in integer arithmetic so shaders/density.glsl gets the same texel.
int gridTexel(int i, int n, int size);

// Maximum of `map` (row width w) over the texels a straight edge from texel a to texel b crosses:
// max(|dx|, |dz|) + 1 texels at equal steps, each rounded to the nearest texel (the seed's "how many
// texels fall on that edge ... the maximum density along the edge"). The walk starts at the
// lexicographically smaller end, so both patches sharing an edge visit the same texels.
// shaders/density.glsl maxDensityAlongEdge() is the same integer arithmetic.
float maxDensityAlongEdge(const std::vector<float>& map, int w, glm::ivec2 a, glm::ivec2 b);

}  // namespace lb
