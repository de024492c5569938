#pragma once
// A CPU selection's instance records on the GPU (render/instanced.h): one host-visible buffer with a
// region per frame slot, written before the slot's frame is recorded, grown by half when a
// selection outgrows it (after the frames in flight are done with the old one). The instanced-grid
// path draws each footprint's records; the mesh path's task shaders read them.
#include <cstdint>
#include <vector>

#include "render/path_drawer.h"
#include "vk/resources.h"

namespace lb {

class InstanceUpload {
 public:
  explicit InstanceUpload(const PathEnv& env);
  // The selection's records into the slot's region, footprint after footprint.
  void upload(int slot, const Selection& selection);
  // Index of the footprint's first record in the whole buffer (what gl_InstanceIndex counts), and
  // how many it has; the slot's records are contiguous from first(slot, 0).
  uint32_t first(int slot, size_t footprint) const { return first_[size_t(slot)][footprint]; }
  uint32_t count(int slot, size_t footprint) const { return count_[size_t(slot)][footprint]; }
  uint32_t total(int slot) const;
  size_t footprints(int slot) const { return count_[size_t(slot)].size(); }
  const Buffer* buffer() const { return records_.buffer ? &records_ : nullptr; }

 private:
  PathEnv env_;
  Buffer records_;  // slots regions of capacity_ records each
  uint32_t capacity_ = 0;
  std::vector<std::vector<uint32_t>> first_, count_;  // per slot and footprint
};

}  // namespace lb
