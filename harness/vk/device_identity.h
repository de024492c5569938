#pragma once
// Which board a run used, beyond its model name: the device's UUID (Vulkan's
// VkPhysicalDeviceIDProperties, core since 1.1) and, on NVIDIA, the board's power limit read
// through NVML (vk/nvml.h). NVML is opened at run time (dlopen "libnvidia-ml.so.1"): no build dependency, and
// a machine without it records the limit as unknown, with the reason, never as 0.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace lb {

// 16 bytes as 32 lowercase hex digits grouped 8-4-4-4-12, e.g. "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f":
// the form nvidia-smi and NVML print after "GPU-".
std::string formatUuid(const uint8_t (&bytes)[VK_UUID_SIZE]);

struct PowerLimit {
  double watts = -1;          // NVML's power management limit; < 0: not read (see reason)
  double enforcedWatts = -1;  // NVML's enforced limit (the lowest of every limit in force); < 0: not read
  std::string reason;         // empty when both were read; else why one or both are unknown
};

constexpr uint32_t kNvidiaVendorId = 0x10de;

// The power limit of the NVIDIA board whose NVML UUID is "GPU-" + deviceUuid (formatUuid's form).
// A vendor other than NVIDIA is not asked (reason "not an NVIDIA device ..."); library names the
// NVML library (tests name a missing one).
PowerLimit readPowerLimit(uint32_t vendorId, const std::string& deviceUuid, const char* library = "libnvidia-ml.so.1");

}  // namespace lb
