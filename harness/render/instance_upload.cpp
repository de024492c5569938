#include "render/instance_upload.h"

#include <algorithm>
#include <cstring>

namespace lb {

InstanceUpload::InstanceUpload(const PathEnv& env) : env_(env), first_(size_t(env.slots)), count_(size_t(env.slots)) {}

void InstanceUpload::upload(int slot, const Selection& selection) {
  const size_t total = selection.instanceCount();
  if (total > capacity_) {
    // Frames in flight read the old buffer: wait for them (rare: the capacity only grows).
    env_.finish();
    capacity_ = uint32_t(std::max<size_t>(256, total + total / 2));
    records_ = createBuffer(env_.ctx, VkDeviceSize(sizeof(InstanceRecord)) * capacity_ * VkDeviceSize(env_.slots),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, {GpuResource::Instances, env_.memory});
    env_.rebind();
  }
  auto* out = static_cast<InstanceRecord*>(records_.mapped) + size_t(slot) * capacity_;
  std::vector<uint32_t>& first = first_[size_t(slot)];
  std::vector<uint32_t>& count = count_[size_t(slot)];
  first.assign(selection.instances.size(), 0);
  count.assign(selection.instances.size(), 0);
  uint32_t next = uint32_t(slot) * capacity_;
  for (size_t f = 0; f < selection.instances.size(); ++f) {
    const auto& records = selection.instances[f];
    if (!records.empty())  // an empty vector's data() may be null, which memcpy must not get
      std::memcpy(out, records.data(), records.size() * sizeof(InstanceRecord));
    out += records.size();
    first[f] = next;
    count[f] = uint32_t(records.size());
    next += uint32_t(records.size());
  }
}

uint32_t InstanceUpload::total(int slot) const {
  uint32_t n = 0;
  for (uint32_t c : count_[size_t(slot)]) n += c;
  return n;
}

}  // namespace lb
