#pragma once
// NVML, opened at run time (dlopen "libnvidia-ml.so.1"): no build dependency. One session opens the
// library, initialises it and finds the NVML device of a Vulkan device by its UUID; the board's
// power limit (vk/device_identity.h), energy counter and clocks (vk/energy_counter.h) are read
// through it. A machine without NVML, or a device that is not NVIDIA's, gives a session that is not
// open, with the reason.
#include <cstdint>
#include <memory>
#include <string>

namespace lb {

constexpr const char* kNvmlLibrary = "libnvidia-ml.so.1";

class NvmlSession {
 public:
  // The NVIDIA board whose NVML UUID is "GPU-" + deviceUuid (vk/device_identity.h formatUuid's
  // form). A vendor other than NVIDIA is not asked ("not an NVIDIA device ..."); library names the
  // NVML library (tests name a missing one).
  NvmlSession(uint32_t vendorId, const std::string& deviceUuid, const char* library = kNvmlLibrary);
  ~NvmlSession();
  NvmlSession(const NvmlSession&) = delete;
  NvmlSession& operator=(const NvmlSession&) = delete;

  bool open() const;
  const std::string& reason() const { return reason_; }  // why not open; "" when open

  // Each returns NVML's return code (0: read); errorText says what another code means. An entry
  // point the library lacks gives kMissingEntryPoint.
  static constexpr int kMissingEntryPoint = -1;
  int powerManagementLimitMw(unsigned& mw) const;
  int enforcedPowerLimitMw(unsigned& mw) const;
  // nvmlDeviceGetTotalEnergyConsumption: millijoules since the driver was loaded.
  int totalEnergyMj(unsigned long long& mj) const;
  enum class Clock { Graphics = 0, Sm = 1, Memory = 2 };  // nvmlClockType_t
  int clockMhz(Clock which, unsigned& mhz) const;         // current
  int maxClockMhz(Clock which, unsigned& mhz) const;      // the board's maximum
  std::string errorText(int code) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string reason_;
};

}  // namespace lb
