#pragma once
// Ground truth for image metrics: a CPU ray cast of the true heightfield, the
// bilinear surface that Heightfield::sample and shaders/common.glsl terrainHeight() define, shaded
// as shaders/terrain.frag shades (raycast_shade.h). Each ray is intersected exactly with every
// bilinear cell it crosses (a quadratic in the ray parameter), front to back, and a max-mipmap
// quadtree skips the nodes the ray passes above (Tevs, Ihrke, Seidel 2008, "Maximum mipmaps for
// fast, accurate, and scalable dynamic height field rendering").
#include <glm/glm.hpp>
#include <vector>

#include "camera/camera_path.h"
#include "metrics/image_metrics.h"

namespace lb {

struct Heightfield;

// Max-mipmap over the heightfield's cells: level 0 holds each cell's largest corner height (the
// bilinear patch never exceeds its corners), level k the max of 2x2 nodes of level k-1.
struct MaxMipmap {
  struct Level {
    int w = 0, h = 0;
    std::vector<float> max;
  };
  std::vector<Level> levels;  // levels.back() is 1 x 1
};
MaxMipmap buildMaxMipmap(const Heightfield& hf);

struct RayHit {
  bool hit = false;
  double t = 0;       // ray parameter of the first hit
  glm::dvec3 pos{0};  // world position, on the bilinear surface
};

// First intersection of o + t d, t in [tMin, tMax], with the heightfield's surface over
// [0, extent]^2 (no surface outside it, as no patch covers it).
RayHit castRay(const Heightfield& hf, const MaxMipmap& mip, glm::dvec3 o, glm::dvec3 d, double tMin, double tMax);

// The frame as the renderer's camera sees it: one ray per pixel centre, between the near and far
// planes of cameraMatrices(pose, width / height, extent); clear colour (magenta) on a miss.
// `distance` (optional) receives the eye-to-hit distance per pixel, -1 on a miss. threads <= 0:
// std::thread::hardware_concurrency().
RgbaImage raycastImage(const Heightfield& hf, const CameraPose& pose, int width, int height,
                       std::vector<float>* distance = nullptr, int threads = 0);

// World-space ray through pixel (px + 0.5, py + 0.5): origin on the near plane, o + d on the far plane.
void pixelRay(const glm::dmat4& invViewProj, int px, int py, int width, int height, glm::dvec3& o, glm::dvec3& d);

}  // namespace lb
