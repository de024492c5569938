// Which board ran a run: the device's UUID from Vulkan and, on NVIDIA, the power
// limit from NVML, in every run's context; compare notes another board of the model without
// calling it a regression.
#include <gtest/gtest.h>

#include <regex>

#include "cli_run.h"
#include "compare/compare.h"
#include "gpu_fixture.h"
#include "synthetic_run.h"
#include "vk/device_identity.h"

using namespace lb;
using nlohmann::json;

namespace {

const std::regex kUuid("^[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}$");

}  // namespace

TEST(DeviceIdentity, UuidIs32HexDigitsGroupedAsNvmlPrintsThem) {
  const uint8_t bytes[VK_UUID_SIZE] = {0x6c, 0x3b, 0x5f, 0x2e, 0x0d, 0x1a, 0x4b, 0x6e,
                                       0x9f, 0x10, 0x2a, 0x3b, 0x4c, 0x5d, 0x6e, 0x7f};
  EXPECT_EQ(formatUuid(bytes), "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f");
  EXPECT_TRUE(std::regex_match(lbtest::gpu().deviceUuid, kUuid)) << lbtest::gpu().deviceUuid;
  EXPECT_TRUE(std::regex_match(lbtest::gpu().driverUuid, kUuid)) << lbtest::gpu().driverUuid;
}

TEST(DeviceIdentity, PowerLimitIsUnknownWithAReasonNeverZero) {
  PowerLimit other = readPowerLimit(0x10005, "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f");  // Mesa's vendor id
  EXPECT_LT(other.watts, 0);
  EXPECT_LT(other.enforcedWatts, 0);
  EXPECT_EQ(other.reason, "not an NVIDIA device (vendor 0x10005): NVML reads NVIDIA boards only");
  PowerLimit noLib =
      readPowerLimit(kNvidiaVendorId, "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f", "libnvidia-ml-absent.so.1");
  EXPECT_LT(noLib.watts, 0);
  EXPECT_EQ(noLib.reason.rfind("NVML not available (", 0), 0u) << noLib.reason;
}

// A real run through the command: run.json's context names the board.
TEST(DeviceIdentity, EveryRunsContextHasTheUuidAndThePowerLimitOrWhyNot) {
  std::string dir = test::freshDir("identity_run");
  test::CliOut o = test::lodbench("run " + test::kTinyConfig + " --out " + dir + " -q", false);
  ASSERT_EQ(o.code, 0) << o.text;
  json ctx = test::readJson(dir + "/run.json")["context"];
  ASSERT_TRUE(ctx.contains("device_uuid"));
  EXPECT_TRUE(std::regex_match(ctx["device_uuid"].get<std::string>(), kUuid)) << ctx["device_uuid"];
  EXPECT_EQ(ctx["device_uuid"], lbtest::gpu().deviceUuid) << "the device the run used";
  EXPECT_TRUE(std::regex_match(ctx["driver_uuid"].get<std::string>(), kUuid)) << ctx["driver_uuid"];
  for (const char* k : {"power_limit_w", "power_limit_enforced_w", "power_limit_reason"})
    EXPECT_TRUE(ctx.contains(k)) << k;
  if (ctx["vendor_id"] != kNvidiaVendorId) {  // lavapipe here
    EXPECT_TRUE(ctx["power_limit_w"].is_null());
    EXPECT_TRUE(ctx["power_limit_enforced_w"].is_null());
    EXPECT_NE(ctx["power_limit_reason"].get<std::string>().find("not an NVIDIA device"), std::string::npos);
  } else if (ctx["power_limit_w"].is_null()) {
    EXPECT_FALSE(ctx["power_limit_reason"].get<std::string>().empty());
  } else {
    EXPECT_GT(ctx["power_limit_w"].get<double>(), 0.0);
  }
  json summary = test::readJson(dir + "/summary.json");
  EXPECT_EQ(summary["context"]["device_uuid"], ctx["device_uuid"]);
}

// Two boards of one model: counters are compared exactly as ever, and a note says the timings
// come from two boards (and two power limits); neither is a regression.
TEST(DeviceIdentity, CompareNotesAnotherBoardOfTheModelWithoutARegression) {
  json a = test::runContext(), b = a;
  a["device_uuid"] = "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f";
  b["device_uuid"] = "0f1e2d3c-4b5a-6978-8796-a5b4c3d2e1f0";
  a["power_limit_w"] = 700.0;
  b["power_limit_w"] = 500.0;
  json c = test::caseDoc("x", test::gpuTimes(20, 1));
  CompareOptions o;
  o.requireExact = true;
  CompareReport r =
      compareRuns(loadRun(test::writeRun("board_a", a, {c})), loadRun(test::writeRun("board_b", b, {c})), o);
  EXPECT_TRUE(r.exactChecked) << r.exactSkipReason;
  EXPECT_EQ(r.exitCode(), 0);
  std::string notes;
  for (auto& n : r.notes) notes += n + "\n";
  EXPECT_NE(notes.find("two boards of one model"), std::string::npos) << notes;
  EXPECT_NE(notes.find("power_limit_w 700.0 W (baseline) vs 500.0 W (candidate)"), std::string::npos) << notes;
  // A baseline recorded before the UUID (results/baseline/ci): no note, nothing refused.
  json old = test::runContext();
  CompareReport r2 =
      compareRuns(loadRun(test::writeRun("board_old", old, {c})), loadRun(test::writeRun("board_b2", b, {c})), o);
  EXPECT_EQ(r2.exitCode(), 0);
  for (auto& n : r2.notes) EXPECT_EQ(n.find("board"), std::string::npos) << n;
}
