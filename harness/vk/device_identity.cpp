#include "vk/device_identity.h"

#include <cstdio>

#include "vk/nvml.h"

namespace lb {

std::string formatUuid(const uint8_t (&bytes)[VK_UUID_SIZE]) {
  std::string s;
  char hex[3];
  for (int i = 0; i < VK_UUID_SIZE; ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) s += '-';
    std::snprintf(hex, sizeof hex, "%02x", unsigned(bytes[i]));
    s += hex;
  }
  return s;
}

PowerLimit readPowerLimit(uint32_t vendorId, const std::string& deviceUuid, const char* library) {
  PowerLimit p;
  const NvmlSession nvml(vendorId, deviceUuid, library);
  if (!nvml.open()) {
    p.reason = nvml.reason();
    return p;
  }
  unsigned mw = 0;
  if (int r = nvml.powerManagementLimitMw(mw); r == 0)
    p.watts = mw / 1000.0;
  else
    p.reason = "power management limit: " + nvml.errorText(r);
  if (int r = nvml.enforcedPowerLimitMw(mw); r == 0)
    p.enforcedWatts = mw / 1000.0;
  else
    p.reason += (p.reason.empty() ? "" : "; ") + std::string("enforced power limit: ") + nvml.errorText(r);
  return p;
}

}  // namespace lb
