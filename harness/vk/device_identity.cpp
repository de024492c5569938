#include "vk/device_identity.h"

#include <dlfcn.h>

#include <cstdio>

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

namespace {

// The few NVML entry points used, as nvml.h declares them (nvmlDevice_t is an opaque pointer,
// nvmlReturn_t an int enum, NVML_SUCCESS 0).
using NvmlDevice = struct NvmlDeviceOpaque*;
using NvmlInit = int (*)();
using NvmlShutdown = int (*)();
using NvmlErrorString = const char* (*)(int);
using NvmlByUuid = int (*)(const char*, NvmlDevice*);
using NvmlCount = int (*)(unsigned*);
using NvmlByIndex = int (*)(unsigned, NvmlDevice*);
using NvmlUuid = int (*)(NvmlDevice, char*, unsigned);
using NvmlLimit = int (*)(NvmlDevice, unsigned*);

struct Library {
  void* handle = nullptr;
  ~Library() {
    if (handle) dlclose(handle);
  }
};

}  // namespace

PowerLimit readPowerLimit(uint32_t vendorId, const std::string& deviceUuid, const char* library) {
  PowerLimit p;
  if (vendorId != kNvidiaVendorId) {
    char v[16];
    std::snprintf(v, sizeof v, "0x%x", vendorId);
    p.reason = std::string("not an NVIDIA device (vendor ") + v + "): NVML reads NVIDIA boards only";
    return p;
  }
  Library lib;
  lib.handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
  if (!lib.handle) {
    const char* e = dlerror();
    p.reason = std::string("NVML not available (") + (e ? e : library) + ")";
    return p;
  }
  auto sym = [&](const char* name) { return dlsym(lib.handle, name); };
  auto init = reinterpret_cast<NvmlInit>(sym("nvmlInit_v2"));
  auto shutdown = reinterpret_cast<NvmlShutdown>(sym("nvmlShutdown"));
  auto errorString = reinterpret_cast<NvmlErrorString>(sym("nvmlErrorString"));
  auto byUuid = reinterpret_cast<NvmlByUuid>(sym("nvmlDeviceGetHandleByUUID"));
  auto count = reinterpret_cast<NvmlCount>(sym("nvmlDeviceGetCount_v2"));
  auto byIndex = reinterpret_cast<NvmlByIndex>(sym("nvmlDeviceGetHandleByIndex_v2"));
  auto uuidOf = reinterpret_cast<NvmlUuid>(sym("nvmlDeviceGetUUID"));
  auto limit = reinterpret_cast<NvmlLimit>(sym("nvmlDeviceGetPowerManagementLimit"));
  auto enforced = reinterpret_cast<NvmlLimit>(sym("nvmlDeviceGetEnforcedPowerLimit"));
  if (!init || !shutdown || !errorString || !byUuid || !limit || !enforced) {
    p.reason = std::string("NVML not available (") + library + " lacks an entry point this needs)";
    return p;
  }
  auto err = [&](int r) { return std::string(errorString(r) ? errorString(r) : "unknown error"); };
  if (int r = init(); r != 0) {
    p.reason = "NVML not available (nvmlInit: " + err(r) + ")";
    return p;
  }
  NvmlDevice dev = nullptr;
  const std::string nvmlUuid = "GPU-" + deviceUuid;
  if (int r = byUuid(nvmlUuid.c_str(), &dev); r != 0) {
    // Say which boards NVML does see: a UUID that matches none is worth reading.
    std::string seen;
    unsigned n = 0;
    if (count && byIndex && uuidOf && count(&n) == 0)
      for (unsigned i = 0; i < n; ++i) {
        NvmlDevice d = nullptr;
        char u[96] = "";
        if (byIndex(i, &d) == 0 && uuidOf(d, u, sizeof u) == 0) seen += std::string(seen.empty() ? "" : ", ") + u;
      }
    p.reason = "no NVML device has this device's UUID " + nvmlUuid + " (" + err(r) + "; NVML lists " +
               (seen.empty() ? std::string("none") : seen) + ")";
    shutdown();
    return p;
  }
  unsigned mw = 0;
  if (int r = limit(dev, &mw); r == 0)
    p.watts = mw / 1000.0;
  else
    p.reason = "power management limit: " + err(r);
  if (int r = enforced(dev, &mw); r == 0)
    p.enforcedWatts = mw / 1000.0;
  else
    p.reason += (p.reason.empty() ? "" : "; ") + std::string("enforced power limit: ") + err(r);
  shutdown();
  return p;
}

}  // namespace lb
