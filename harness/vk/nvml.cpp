#include "vk/nvml.h"

#include <dlfcn.h>

#include <cstdio>

#include "vk/device_identity.h"

namespace lb {

namespace {

// The few NVML entry points used, as nvml.h declares them (nvmlDevice_t is an opaque pointer,
// nvmlReturn_t an int enum, NVML_SUCCESS 0, nvmlClockType_t an int enum).
using NvmlDevice = struct NvmlDeviceOpaque*;
using NvmlInit = int (*)();
using NvmlShutdown = int (*)();
using NvmlErrorString = const char* (*)(int);
using NvmlByUuid = int (*)(const char*, NvmlDevice*);
using NvmlCount = int (*)(unsigned*);
using NvmlByIndex = int (*)(unsigned, NvmlDevice*);
using NvmlUuid = int (*)(NvmlDevice, char*, unsigned);
using NvmlLimit = int (*)(NvmlDevice, unsigned*);
using NvmlEnergy = int (*)(NvmlDevice, unsigned long long*);
using NvmlClockInfo = int (*)(NvmlDevice, int, unsigned*);

}  // namespace

struct NvmlSession::Impl {
  std::string library;
  void* handle = nullptr;
  bool initialised = false;
  NvmlDevice device = nullptr;
  NvmlShutdown shutdown = nullptr;
  NvmlErrorString errorString = nullptr;
  NvmlLimit limit = nullptr, enforced = nullptr;
  NvmlEnergy energy = nullptr;
  NvmlClockInfo clock = nullptr, maxClock = nullptr;
  ~Impl() {
    if (initialised) shutdown();
    if (handle) dlclose(handle);
  }
};

NvmlSession::NvmlSession(uint32_t vendorId, const std::string& deviceUuid, const char* library) {
  if (vendorId != kNvidiaVendorId) {
    char v[16];
    std::snprintf(v, sizeof v, "0x%x", vendorId);
    reason_ = std::string("not an NVIDIA device (vendor ") + v + "): NVML reads NVIDIA boards only";
    return;
  }
  auto impl = std::make_unique<Impl>();
  impl->library = library;
  impl->handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
  if (!impl->handle) {
    const char* e = dlerror();
    reason_ = std::string("NVML not available (") + (e ? e : library) + ")";
    return;
  }
  auto sym = [&](const char* name) { return dlsym(impl->handle, name); };
  auto init = reinterpret_cast<NvmlInit>(sym("nvmlInit_v2"));
  impl->shutdown = reinterpret_cast<NvmlShutdown>(sym("nvmlShutdown"));
  impl->errorString = reinterpret_cast<NvmlErrorString>(sym("nvmlErrorString"));
  auto byUuid = reinterpret_cast<NvmlByUuid>(sym("nvmlDeviceGetHandleByUUID"));
  auto count = reinterpret_cast<NvmlCount>(sym("nvmlDeviceGetCount_v2"));
  auto byIndex = reinterpret_cast<NvmlByIndex>(sym("nvmlDeviceGetHandleByIndex_v2"));
  auto uuidOf = reinterpret_cast<NvmlUuid>(sym("nvmlDeviceGetUUID"));
  impl->limit = reinterpret_cast<NvmlLimit>(sym("nvmlDeviceGetPowerManagementLimit"));
  impl->enforced = reinterpret_cast<NvmlLimit>(sym("nvmlDeviceGetEnforcedPowerLimit"));
  impl->energy = reinterpret_cast<NvmlEnergy>(sym("nvmlDeviceGetTotalEnergyConsumption"));
  impl->clock = reinterpret_cast<NvmlClockInfo>(sym("nvmlDeviceGetClockInfo"));
  impl->maxClock = reinterpret_cast<NvmlClockInfo>(sym("nvmlDeviceGetMaxClockInfo"));
  if (!init || !impl->shutdown || !impl->errorString || !byUuid) {
    reason_ = std::string("NVML not available (") + library + " lacks an entry point this needs)";
    return;
  }
  impl_ = std::move(impl);
  if (int r = init(); r != 0) {
    reason_ = "NVML not available (nvmlInit: " + errorText(r) + ")";
    impl_.reset();
    return;
  }
  impl_->initialised = true;
  const std::string nvmlUuid = "GPU-" + deviceUuid;
  if (int r = byUuid(nvmlUuid.c_str(), &impl_->device); r != 0) {
    // Say which boards NVML does see: a UUID that matches none is worth reading.
    std::string seen;
    unsigned n = 0;
    if (count && byIndex && uuidOf && count(&n) == 0)
      for (unsigned i = 0; i < n; ++i) {
        NvmlDevice d = nullptr;
        char u[96] = "";
        if (byIndex(i, &d) == 0 && uuidOf(d, u, sizeof u) == 0) seen += std::string(seen.empty() ? "" : ", ") + u;
      }
    reason_ = "no NVML device has this device's UUID " + nvmlUuid + " (" + errorText(r) + "; NVML lists " +
              (seen.empty() ? std::string("none") : seen) + ")";
    impl_.reset();
  }
}

NvmlSession::~NvmlSession() = default;

bool NvmlSession::open() const {
  return impl_ != nullptr;
}

std::string NvmlSession::errorText(int code) const {
  if (code == kMissingEntryPoint)
    return (impl_ ? impl_->library : std::string(kNvmlLibrary)) + " lacks the entry point";
  const char* s = impl_ && impl_->errorString ? impl_->errorString(code) : nullptr;
  return s ? s : "unknown error";
}

int NvmlSession::powerManagementLimitMw(unsigned& mw) const {
  return impl_ && impl_->limit ? impl_->limit(impl_->device, &mw) : kMissingEntryPoint;
}

int NvmlSession::enforcedPowerLimitMw(unsigned& mw) const {
  return impl_ && impl_->enforced ? impl_->enforced(impl_->device, &mw) : kMissingEntryPoint;
}

int NvmlSession::totalEnergyMj(unsigned long long& mj) const {
  return impl_ && impl_->energy ? impl_->energy(impl_->device, &mj) : kMissingEntryPoint;
}

int NvmlSession::clockMhz(Clock which, unsigned& mhz) const {
  return impl_ && impl_->clock ? impl_->clock(impl_->device, int(which), &mhz) : kMissingEntryPoint;
}

int NvmlSession::maxClockMhz(Clock which, unsigned& mhz) const {
  return impl_ && impl_->maxClock ? impl_->maxClock(impl_->device, int(which), &mhz) : kMissingEntryPoint;
}

}  // namespace lb
