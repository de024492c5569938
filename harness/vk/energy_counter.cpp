#include "vk/energy_counter.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <thread>

#include "vk/nvml.h"

namespace lb {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double EnergyCounter::now() const {
  return steadySeconds();
}

GpuClocks EnergyCounter::clocks() const {
  GpuClocks c;
  c.reason = "the " + name() + " counter reads no clocks";
  return c;
}

StandInEnergyCounter::StandInEnergyCounter(double tickS, double watts, std::function<double()> clock)
    : tickS_(tickS), watts_(watts), clock_(std::move(clock)), origin_(clock_()) {
  if (!(tickS_ > 0) || !(watts_ >= 0)) reason_ = "stand-in energy counter needs a tick > 0 and watts >= 0";
}

std::optional<uint64_t> StandInEnergyCounter::readMj() {
  // Whole ticks since the origin (the small term keeps a tick boundary reached exactly on its side).
  const double ticks = std::floor((clock_() - origin_) / tickS_ + 1e-9);
  return uint64_t(std::llround(ticks * watts_ * tickS_ * 1000.0));
}

GpuClocks StandInEnergyCounter::clocks() const {
  GpuClocks c;
  c.reason = "a stand-in energy counter (tests): no clocks";
  return c;
}

NvmlEnergyCounter::NvmlEnergyCounter(uint32_t vendorId, const std::string& deviceUuid, const char* library)
    : nvml_(std::make_unique<NvmlSession>(vendorId, deviceUuid, library ? library : kNvmlLibrary)) {
  if (!nvml_->open()) {
    reason_ = nvml_->reason();
    return;
  }
  unsigned long long mj = 0;
  if (int r = nvml_->totalEnergyMj(mj); r != 0) reason_ = "NVML total energy counter: " + nvml_->errorText(r);
}

NvmlEnergyCounter::~NvmlEnergyCounter() {
  stop_ = true;
  if (sampler_.joinable()) sampler_.join();
}

std::optional<uint64_t> NvmlEnergyCounter::readMj() {
  if (!nvml_->open()) {
    readError_ = nvml_->reason();
    return std::nullopt;
  }
  if (!sampler_.joinable()) {  // the first read: one in this thread, then the sampler's
    unsigned long long mj = 0;
    if (int r = nvml_->totalEnergyMj(mj); r != 0) {
      readError_ = "NVML total energy counter: " + nvml_->errorText(r);
      return std::nullopt;
    }
    latest_ = mj;
    sampler_ = std::thread([this] {
      while (!stop_) {
        unsigned long long v = 0;
        if (int r = nvml_->totalEnergyMj(v); r != 0) {
          error_ = r;
          return;
        }
        latest_ = v;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  }
  if (int r = error_.load(); r != 0) {
    readError_ = "NVML total energy counter: " + nvml_->errorText(r);
    return std::nullopt;
  }
  return latest_.load();
}

GpuClocks NvmlEnergyCounter::clocks() const {
  GpuClocks c;
  if (!nvml_->open()) {
    c.reason = nvml_->reason();
    return c;
  }
  using Clock = NvmlSession::Clock;
  auto read = [&](const char* what, bool max, Clock which, int& out) {
    unsigned mhz = 0;
    int r = max ? nvml_->maxClockMhz(which, mhz) : nvml_->clockMhz(which, mhz);
    if (r == 0)
      out = int(mhz);
    else
      c.reason += (c.reason.empty() ? "" : "; ") + std::string(what) + ": " + nvml_->errorText(r);
  };
  read("SM clock", false, Clock::Sm, c.smMhz);
  read("memory clock", false, Clock::Memory, c.memMhz);
  read("SM max clock", true, Clock::Sm, c.smMaxMhz);
  read("memory max clock", true, Clock::Memory, c.memMaxMhz);
  return c;
}

std::unique_ptr<EnergyCounter> openEnergyCounter(uint32_t vendorId, const std::string& deviceUuid) {
  if (const char* e = std::getenv("LODBENCH_TEST_ENERGY_COUNTER"); e && *e) {
    const std::string s = e;
    const size_t colon = s.find(':');
    const double tickMs = std::atof(s.substr(0, colon).c_str());
    const double watts = colon == std::string::npos ? 0 : std::atof(s.substr(colon + 1).c_str());
    return std::make_unique<StandInEnergyCounter>(tickMs / 1000.0, watts);
  }
  return std::make_unique<NvmlEnergyCounter>(vendorId, deviceUuid);
}

double measureTickMs(EnergyCounter& counter, double timeoutS) {
  if (!counter.available()) return -1;
  const double deadline = steadySeconds() + timeoutS;
  std::optional<uint64_t> last = counter.readMj();
  int changes = 0;
  double firstChange = 0, lastChange = 0;
  while (last && steadySeconds() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::optional<uint64_t> v = counter.readMj();
    if (!v) return -1;
    if (*v == *last) continue;
    last = v;
    lastChange = counter.now();
    if (++changes == 1) firstChange = lastChange;
    // The mean over up to 20 intervals (at most 1 s of them): a poll that wakes late under load
    // shortens one interval and lengthens the next, so one interval alone can be off by the delay.
    if (changes > 20 || (changes >= 2 && lastChange - firstChange >= 1.0)) break;
  }
  return changes >= 2 ? 1000.0 * (lastChange - firstChange) / double(changes - 1) : -1;
}

}  // namespace lb
