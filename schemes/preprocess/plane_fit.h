#pragma once
// practical-d3d11-ch9 9.1.2 "Pre-Processing the Height Map" (Listings 9.10-9.16) on the CPU, the
// reference for shaders/planefit.comp (same float arithmetic in the same order). The heightfield
// is cut into LB_PLANE_FIT_BLOCK^2-sample blocks from sample (0, 0); blocks past the border repeat
// the last sample, as the shader's clamped texelFetch does. Per block: a plane normal and a
// coplanarity measure (standard deviation of the samples' distances to the plane).
#include <glm/glm.hpp>
#include <vector>

namespace lb {

struct Heightfield;

enum class PlaneFit {
  // The listings: normal = normalized sum of the four corner normals, plane through the lowest
  // corner; corners at x, z in {0, 1/64} but samples at {0..15}/15; heights normalized to [0, 1]
  // as the book's UNORM texture delivers them; sqrt(sum d^2 / 255), uncentred.
  Book = 0,
  // Corrected: least-squares height plane y = a + b x + c z over all samples in world units
  // (block-centred x, z), perpendicular distances, centred standard deviation over all samples.
  LeastSquares = 1,
};

struct PlaneFitBlock {
  glm::vec3 normal{0, 1, 0};  // unit plane normal (the book's is in its own scaled coordinates)
  float deviation = 0;        // coplanarity: book = normalized-height units, lsq = world units
};

struct PlaneFitResult {
  int width = 0, height = 0;          // blocks along x and z
  std::vector<PlaneFitBlock> blocks;  // row-major, row = z
  const PlaneFitBlock& at(int bx, int bz) const { return blocks[size_t(bz) * size_t(width) + size_t(bx)]; }
};

int planeFitBlockCount(int samples);  // blocks along an axis of `samples` samples: ceil(samples / 16)
PlaneFitBlock fitBlock(const Heightfield& hf, int bx, int bz, PlaneFit fit);
PlaneFitResult fitPlanes(const Heightfield& hf, PlaneFit fit);

}  // namespace lb
