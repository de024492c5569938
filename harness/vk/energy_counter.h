#pragma once
// A GPU's energy counter: a total in millijoules that the board advances in ticks (NVML's
// nvmlDeviceGetTotalEnergyConsumption, every 100 ms on the H100), read by the energy pass
// (replay/energy_pass.h) over windows of whole ticks. NVML is opened at run time (vk/nvml.h): no
// build dependency; a device without a counter gets one that is not available, with the reason.
// Tests use the stand-in, which advances in fixed ticks of a known period at a known power.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>

namespace lb {

class NvmlSession;

// NVML's current and maximum clocks of a board, MHz; < 0: not read (reason says why).
struct GpuClocks {
  int smMhz = -1, memMhz = -1, smMaxMhz = -1, memMaxMhz = -1;
  std::string reason;  // "" when all four were read
};

class EnergyCounter {
 public:
  virtual ~EnergyCounter() = default;
  bool available() const { return reason_.empty(); }
  const std::string& reason() const { return reason_; }  // why not available; "" when it is
  // The counter now, in millijoules from a fixed origin (NVML: the driver's load); nullopt when a
  // read fails (readError says why).
  virtual std::optional<uint64_t> readMj() = 0;
  const std::string& readError() const { return readError_; }
  // Seconds on the clock the counter's ticks follow (steady_clock; a test's stand-in may bring its own).
  virtual double now() const;
  // The board's clocks right now (the energy pass reads them at the end of each window).
  virtual GpuClocks clocks() const;
  virtual std::string name() const = 0;  // "NVML total energy", "stand-in"

 protected:
  std::string reason_, readError_;
};

// Seconds since an arbitrary origin, on std::chrono::steady_clock.
double steadySeconds();

// The stand-in for tests: tickS apart it adds watts x tickS joules, so a load drawing a frame every
// d seconds costs watts x d joules a frame, quantised to whole ticks. clock: seconds (default
// steadySeconds); the origin is the clock at construction.
class StandInEnergyCounter : public EnergyCounter {
 public:
  StandInEnergyCounter(double tickS, double watts, std::function<double()> clock = steadySeconds);
  std::optional<uint64_t> readMj() override;
  double now() const override { return clock_(); }
  GpuClocks clocks() const override;
  std::string name() const override { return "stand-in"; }
  double tickS() const { return tickS_; }
  double watts() const { return watts_; }

 private:
  double tickS_, watts_;
  std::function<double()> clock_;
  double origin_;
};

// NVML's total-energy counter of the NVIDIA board whose UUID is deviceUuid; not available (with
// the reason: "not an NVIDIA device ...", "NVML not available (...)", NVML's error for the counter)
// where it cannot be read. An NVML read blocks its thread for milliseconds: on an H100 (driver
// 580) a render loop reading it after every frame ran at 3.6 ms a frame instead of the timed loop's
// 0.96 ms, its GPU idle most of the time. So a sampler thread reads NVML continuously from the
// first readMj on, and readMj returns its latest value without waiting.
class NvmlEnergyCounter : public EnergyCounter {
 public:
  NvmlEnergyCounter(uint32_t vendorId, const std::string& deviceUuid, const char* library = nullptr);
  ~NvmlEnergyCounter() override;
  std::optional<uint64_t> readMj() override;
  GpuClocks clocks() const override;
  std::string name() const override { return "NVML total energy"; }

 private:
  std::unique_ptr<NvmlSession> nvml_;
  std::thread sampler_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> latest_{0};
  std::atomic<int> error_{0};  // NVML's code of a failed read by the sampler; 0: none
};

// The counter a run uses: LODBENCH_TEST_ENERGY_COUNTER="<tick_ms>:<watts>" gives the stand-in
// (tests), else NVML's for the device.
std::unique_ptr<EnergyCounter> openEnergyCounter(uint32_t vendorId, const std::string& deviceUuid);

// The counter's tick measured: polls (every 1 ms) and returns the mean time between its changes
// in ms, over up to 20 intervals or the first second of them; < 0 when it did not change twice
// within timeoutS.
double measureTickMs(EnergyCounter& counter, double timeoutS);

}  // namespace lb
