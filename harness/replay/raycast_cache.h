#pragma once
// Persistent cache of ray-cast ground-truth images (metrics/raycast.h), one per terrain,
// resolution and camera pose, shared by every case of a sweep.
#include <map>
#include <memory>
#include <string>

#include "camera/camera_path.h"
#include "metrics/image_metrics.h"
#include "render/frame_data.h"
#include "replay/surplus.h"

namespace lb {

struct Context;
struct Heightfield;
class MeasureGpu;

// Ground truth of a frame: the ray cast of the true heightfield (metrics/raycast.h), made once
// per terrain, resolution and camera pose and kept for every case of a sweep. With a directory,
// each image is written there (<dir>/<terrain>_<w>x<h>_<key hash>.png) as soon as it is made and
// read back instead of ray cast again, so a resumed sweep loses no ray casts to a kill. The key
// hashes everything that defines the image: the heights themselves, extent, resolution, pose.
class ReferenceCache {
 public:
  ReferenceCache();
  explicit ReferenceCache(std::string dir);
  ~ReferenceCache();
  // ctx is unused (the ground truth is made on the CPU); kept so callers need not change.
  const RgbaImage& image(Context& ctx, const Heightfield& terrain, const std::string& terrainKey,
                         const RenderSettings& settings, const CameraPose& pose);
  const RgbaImage& image(const Heightfield& terrain, const std::string& terrainKey, int width, int height,
                         const CameraPose& pose);
  // Buffers, ray cast and reductions of measurement on the GPU (replay/measure_gpu.h) for this terrain
  // (terrainKey names its contents) and resolution, made anew when either changes.
  MeasureGpu& gpu(Context& ctx, const Heightfield& terrain, const std::string& terrainKey, int width, int height);
  SurplusMatcher surplus;  // error-bounded scheme's renderer for the surplus search, kept across the sweep's frames
  int rayCasts() const { return rayCasts_; }                 // images made in this process
  int loaded() const { return loaded_; }                     // images read back from the directory
  double rayCastSeconds() const { return rayCastSeconds_; }  // wall time of those ray casts (progress ETA)
  // The file an image of this terrain, resolution and pose is kept in ("" without a directory).
  std::string file(const Heightfield& terrain, const std::string& terrainKey, int width, int height,
                   const CameraPose& pose) const;

 private:
  std::string dir_;
  std::unique_ptr<MeasureGpu> gpu_;
  std::string gpuKey_;
  std::map<std::string, RgbaImage> images_;
  int rayCasts_ = 0, loaded_ = 0;
  double rayCastSeconds_ = 0;
};

}  // namespace lb
