#include "schemes/preprocess/plane_fit.h"

#include <cmath>

#include "shaders/shared.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

constexpr int kB = LB_PLANE_FIT_BLOCK;
constexpr int kLast = kB - 1;
constexpr int kN = kB * kB;

// Samples of one block in SV_GroupIndex order (gi = gy * 16 + gx), clamped at the border.
void loadBlock(const Heightfield& hf, int bx, int bz, float* h) {
  for (int gi = 0; gi < kN; ++gi) h[gi] = hf.at(bx * kB + gi % kB, bz * kB + gi / kB);
}

// Listings 9.12-9.16 with two transcription errors fixed: rawNormals[0][8] -> [0][0] and the corner
// loop's "i = 8" -> 0 (Listing 9.14); ComputeDistanceFromPlane's "- plane.w" -> "+ plane.w", since
// with the listing's own D = -(N . P) (equation 9.1) a point on the plane must give 0, as the
// comment of Listing 9.16 states; "- plane.w" would measure the block's height, not its flatness.
PlaneFitBlock bookBlock(const Heightfield& hf, float* h) {
  const float range = hf.maxHeight > hf.minHeight ? hf.maxHeight - hf.minHeight : 1.0f;
  for (int gi = 0; gi < kN; ++gi) h[gi] = (h[gi] - hf.minHeight) / range;
  glm::vec3 c[2][2];  // corners[x][z], "unfairly biased" x/z scaled by 1/64 as in Listing 9.12
  for (int x = 0; x < 2; ++x)
    for (int z = 0; z < 2; ++z) c[x][z] = glm::vec3(float(x) / 64.0f, h[z * kLast * kB + x * kLast], float(z) / 64.0f);
  glm::vec3 n00 = glm::normalize(glm::cross(c[0][1] - c[0][0], c[1][0] - c[0][0]));
  glm::vec3 n10 = glm::normalize(glm::cross(c[0][0] - c[1][0], c[1][1] - c[1][0]));
  glm::vec3 n01 = glm::normalize(glm::cross(c[1][1] - c[0][1], c[0][0] - c[0][1]));
  glm::vec3 n11 = glm::normalize(glm::cross(c[1][0] - c[1][1], c[0][1] - c[1][1]));
  glm::vec3 n = glm::normalize(n00 + n01 + n10 + n11);
  glm::vec3 p(0.0f, 1e9f, 0.0f);  // the lowest corner
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      if (c[i][j].y < p.y) p = c[i][j];
  const float w = -n.x * p.x - n.y * p.y - n.z * p.z;  // CreatePlaneFromPointAndNormal
  float sum = 0.0f;
  for (int gi = 0; gi < kN; ++gi) {
    glm::vec3 s(float(gi % kB) / 15.0f, h[gi], float(gi / kB) / 15.0f);
    float d = glm::dot(n, s) + w;
    sum += d * d;
  }
  return {n, std::sqrt(sum / (float(kN) - 1.0f))};
}

PlaneFitBlock leastSquaresBlock(const Heightfield& hf, const float* h) {
  const float sx = hf.extent / float(std::max(hf.width - 1, 1));
  const float sz = hf.extent / float(std::max(hf.height - 1, 1));
  auto x = [&](int gi) { return (float(gi % kB) - 7.5f) * sx; };
  auto z = [&](int gi) { return (float(gi / kB) - 7.5f) * sz; };
  float sy = 0.0f;
  for (int gi = 0; gi < kN; ++gi) sy += h[gi];
  const float mean = sy / float(kN);
  // Centred coordinates: sum x = sum z = sum xz = 0, so the normal equations decouple.
  float sxy = 0.0f, szy = 0.0f, sxx = 0.0f, szz = 0.0f;
  for (int gi = 0; gi < kN; ++gi) {
    const float y = h[gi] - mean;
    sxy += x(gi) * y;
    szy += z(gi) * y;
    sxx += x(gi) * x(gi);
    szz += z(gi) * z(gi);
  }
  const glm::vec3 n = glm::normalize(glm::vec3(-sxy / sxx, 1.0f, -szy / szz));
  float sd = 0.0f;
  for (int gi = 0; gi < kN; ++gi) sd += glm::dot(n, glm::vec3(x(gi), h[gi] - mean, z(gi)));
  const float dMean = sd / float(kN);
  float var = 0.0f;
  for (int gi = 0; gi < kN; ++gi) {
    const float d = glm::dot(n, glm::vec3(x(gi), h[gi] - mean, z(gi))) - dMean;
    var += d * d;
  }
  return {n, std::sqrt(var / float(kN))};
}

}  // namespace

int planeFitBlockCount(int samples) {
  return (samples + kB - 1) / kB;
}

PlaneFitBlock fitBlock(const Heightfield& hf, int bx, int bz, PlaneFit fit) {
  float h[kN];
  loadBlock(hf, bx, bz, h);
  return fit == PlaneFit::Book ? bookBlock(hf, h) : leastSquaresBlock(hf, h);
}

PlaneFitResult fitPlanes(const Heightfield& hf, PlaneFit fit) {
  PlaneFitResult r;
  r.width = planeFitBlockCount(hf.width);
  r.height = planeFitBlockCount(hf.height);
  r.blocks.resize(size_t(r.width) * size_t(r.height));
  // Blocks are independent: bands of block rows on every hardware thread give the same result.
  parallelRows(
      r.height,
      [&](int bz0, int bz1) {
        for (int bz = bz0; bz < bz1; ++bz)
          for (int bx = 0; bx < r.width; ++bx)
            r.blocks[size_t(bz) * size_t(r.width) + size_t(bx)] = fitBlock(hf, bx, bz, fit);
      },
      4);
  return r;
}

}  // namespace lb
