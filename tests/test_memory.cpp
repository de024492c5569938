// Memory as a result: the create helpers charge exactly what the device allocated to a tag, every
// renderer allocation lands in its own account and nothing outside the helpers allocates; a case
// records its renderer's bytes by resource and its host peak, and null with a reason where unknown.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "config/config.h"
#include "gpu_fixture.h"
#include "host_memory.h"
#include "render/instanced.h"
#include "report/equal_error.h"
#include "report/memory_table.h"
#include "results/memory_json.h"
#include "sweep/runner.h"
#include "terrain/normal_map.h"
#include "vk/gpu_memory.h"

using namespace lb;
using lbtest::gpu;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::array<uint64_t, kGpuResources> processLive() {
  std::array<uint64_t, kGpuResources> out{};
  for (int r = 0; r < kGpuResources; ++r) out[size_t(r)] = gpuBytesLive(GpuResource(r));
  return out;
}

class GpuMemory : public lbtest::GpuTest {};

}  // namespace

// The charge is the allocation the device asked for (its memory requirements, queried here
// independently), against the kind and account of the tag, and comes back on release.
TEST_F(GpuMemory, HelpersChargeWhatTheDeviceAllocated) {
  Context& ctx = gpu();
  const auto before = processLive();
  GpuMemoryAccount account;
  {
    Buffer b = createBuffer(ctx, 1000, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true, {GpuResource::Instances, &account});
    Buffer d = createBufferWithData(ctx, std::vector<uint8_t>(333, 7).data(), 333, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    {GpuResource::Geometry, &account});
    Image img = createImage(ctx, 37, 21, VK_FORMAT_R16G16_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                            {GpuResource::NormalMap, &account}, 6);
    VkMemoryRequirements rb, rd, ri;
    vkGetBufferMemoryRequirements(ctx.device, b.buffer, &rb);
    vkGetBufferMemoryRequirements(ctx.device, d.buffer, &rd);
    vkGetImageMemoryRequirements(ctx.device, img.image, &ri);
    EXPECT_EQ(account.bytes(GpuResource::Instances), rb.size);
    EXPECT_EQ(account.bytes(GpuResource::Geometry), rd.size);
    EXPECT_EQ(account.bytes(GpuResource::NormalMap), ri.size);
    EXPECT_GE(rb.size, 1000u);
    EXPECT_GE(rd.size, 333u);
    // Six levels of a 37 x 21 image of 4-byte texels: at least every level's texels.
    EXPECT_GE(ri.size, VkDeviceSize(4 * (37 * 21 + 18 * 10 + 9 * 5 + 4 * 2 + 2 * 1 + 1 * 1)));
    EXPECT_EQ(account.bytes(GpuResource::Staging), 0u) << "createBufferWithData's staging is gone after the copy";
    EXPECT_EQ(gpuBytesLive(GpuResource::Instances) - before[size_t(GpuResource::Instances)], rb.size);
    b = {};
    EXPECT_EQ(account.bytes(GpuResource::Instances), 0u);
  }
  for (int r = 0; r < kGpuResources; ++r) EXPECT_EQ(account.live[size_t(r)], 0u) << gpuResourceName(GpuResource(r));
  EXPECT_EQ(processLive(), before);
}

// Every device allocation goes through the helpers that charge it: vkAllocateMemory is called in
// vk/resources.cpp and nowhere else in the harness or the schemes.
TEST(GpuMemorySource, OnlyTheHelpersAllocate) {
  const fs::path root = LODBENCH_SOURCE_DIR;
  int inHelpers = 0;
  for (const char* dir : {"harness", "schemes"})
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      std::ifstream f(e.path());
      const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
      if (text.find("vkAllocateMemory(") == std::string::npos) continue;
      if (fs::relative(e.path(), root) == fs::path("harness/vk/resources.cpp"))
        ++inHelpers;
      else
        ADD_FAILURE() << e.path() << " allocates device memory outside vk/resources.cpp: it would not be counted";
    }
  EXPECT_EQ(inHelpers, 1);
}

// Every scheme the test device draws: all of a renderer's allocations are charged to its own
// account under a kind (none untagged), the terrain's images at least their texels, a path's
// instance records at least what a frame drew, and everything comes back when it is released.
TEST_F(GpuMemory, EverySchemeChargesItsRenderer) {
  const Heightfield& t = lbtest::testTerrain();
  const NormalMap normals = computeNormalMap(t);
  for (const Scheme* s : lbtest::drawableSchemes()) {
    SCOPED_TRACE(s->info().name);
    const auto before = processLive();
    {
      Renderer r(gpu(), t, {64, 48, 4});
      r.setScheme(*s, {});
      const FrameResult f = lbtest::renderOnce(r, lbtest::overviewPose());
      const GpuMemoryAccount& a = r.gpuMemory();
      const auto now = processLive();
      for (int k = 0; k < kGpuResources; ++k)
        EXPECT_EQ(now[size_t(k)] - before[size_t(k)], a.live[size_t(k)])
            << gpuResourceName(GpuResource(k)) << ": an allocation of the renderer is charged to no account";
      EXPECT_EQ(a.bytes(GpuResource::Other), 0u) << "an untagged allocation";
      EXPECT_EQ(a.bytes(GpuResource::Staging), 0u);
      EXPECT_GE(a.bytes(GpuResource::Heights), uint64_t(t.width) * uint64_t(t.height) * 4);
      EXPECT_GE(a.bytes(GpuResource::NormalMap), uint64_t(normals.texels.size()) * 2);
      EXPECT_GE(a.bytes(GpuResource::Frame), uint64_t(64 * 48) * 4 * 2);  // colour and depth at least
      EXPECT_GT(a.bytes(GpuResource::Geometry), 0u);
      EXPECT_GT(a.bytes(GpuResource::Capture), 0u);
      if (f.lodMs >= 0 && f.instances > 0) {  // instanced grid, GPU-indirect
        EXPECT_GE(a.bytes(GpuResource::Instances), uint64_t(f.instances) * sizeof(InstanceRecord));
      } else {
        EXPECT_EQ(a.bytes(GpuResource::Instances), 0u);
      }
      EXPECT_EQ(a.bytes(GpuResource::LodState) > 0, r.hasLodState());
      const json m = memoryJson(&a, "", hostPeak(false));
      uint64_t sum = 0;
      for (const auto& [k, v] : m["gpu_bytes"].items()) sum += v.get<uint64_t>();
      EXPECT_EQ(m["gpu_total_bytes"].get<uint64_t>(), sum);
      EXPECT_EQ(m["gpu_capture_bytes"].get<uint64_t>(), a.bytes(GpuResource::Capture));
      EXPECT_EQ(m["gpu_lod_bytes"].get<uint64_t>(),
                a.bytes(GpuResource::SchemeTables) + a.bytes(GpuResource::Geometry) + a.bytes(GpuResource::Instances) +
                    a.bytes(GpuResource::LodState));
    }
    EXPECT_EQ(processLive(), before) << "a charge outlived its renderer";
  }
}

// The host peak: reset to the resident set, it covers at least a block touched since.
TEST(HostMemory, PeakSeesMemoryTouchedSinceTheReset) {
  const bool reset = resetHostPeak();
  const HostPeak a = hostPeak(reset);
  ASSERT_GE(a.bytes, 0) << a.reason;
  {
    std::vector<uint8_t> block(64u << 20);
    for (size_t i = 0; i < block.size(); i += 4096) block[i] = uint8_t(1 + i / 4096 % 255);
    EXPECT_GT(block[4096], 0);  // keeps the writes
  }
  const HostPeak b = hostPeak(reset);
  ASSERT_GE(b.bytes, 0) << b.reason;
  EXPECT_GE(b.bytes, int64_t(64u << 20));
  if (reset) EXPECT_GE(b.bytes, a.bytes + int64_t(60u << 20));  // else the peak may predate the block
}

// A run's case records: memory in every finished case's summary, the device figure the renderer's,
// the host peak at least the terrain's heights and below the machine's memory.
TEST(MemoryRecord, CasesRecordMemoryOrWhyNot) {
  const fs::path out = fs::path(::testing::TempDir()) / "memory_record";
  fs::remove_all(out);
  Config c = parseConfig(R"({
    "name": "memory", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0, "max_frames": 2,
    "measure": {"every": 2}, "images": {"modes": []},
    "terrain": {"type": "procedural", "size": 257, "seed": 3},
    "paths": ["paths/flyover.csv"],
    "schemes": ["uniform", "cdlod", "cbt", "sphere-ms"]
  })",
                         "memory.json", std::string(LODBENCH_SOURCE_DIR) + "/configs");
  const RunTotals totals = runSweep(c, {out.string(), false, false});
  EXPECT_EQ(totals.ok + totals.skipped, 4);
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  for (const auto& e : fs::directory_iterator(out / "cases")) {
    std::ifstream f(e.path());
    const json cj = json::parse(f);
    SCOPED_TRACE(cj["case_id"].get<std::string>());
    const json& m = cj["summary"]["memory"];
    if (cj["status"] != "ok") {  // sphere-ms where the device lacks mesh shaders: no summary, the reason says why
      EXPECT_EQ(cj["status"], "skipped");
      EXPECT_TRUE(cj["summary"].empty());
      EXPECT_FALSE(cj["reason"].get<std::string>().empty());
      continue;
    }
    ASSERT_TRUE(m.is_object());
    EXPECT_TRUE(m["gpu_reason"].is_null());
    EXPECT_GE(m["gpu_bytes"]["heights"].get<uint64_t>(), 257u * 257u * 4u);
    EXPECT_EQ(m["gpu_bytes"]["other"].get<uint64_t>(), 0u);
    EXPECT_GT(m["gpu_total_bytes"].get<uint64_t>(), m["gpu_lod_bytes"].get<uint64_t>());
    ASSERT_TRUE(m["host_peak_bytes"].is_number()) << m["host_reason"];
    // "process" only where the kernel refuses the reset (then this process cannot reset it either).
    EXPECT_EQ(m["host_peak_scope"], resetHostPeak() ? "case" : "process");
    EXPECT_GE(m["host_peak_bytes"].get<int64_t>(), int64_t(257 * 257 * 4));
    EXPECT_LT(m["host_peak_bytes"].get<double>(), double(pages) * double(pageSize));
    if (cj["scheme"] == "cbt") EXPECT_GT(m["gpu_bytes"]["lod_state"].get<uint64_t>(), 0u);
    if (cj["scheme"] == "cdlod") EXPECT_GT(m["gpu_bytes"]["instances"].get<uint64_t>(), 0u);
    if (cj["scheme"] == "uniform") EXPECT_EQ(m["gpu_bytes"]["instances"].get<uint64_t>(), 0u);
  }
}

// Unknown figures are null with the reason beside them, never 0.
TEST(MemoryRecord, UnknownIsNullWithAReason) {
  HostPeak unknownHost;
  unknownHost.reason = "no /proc/self/status";
  const json m = memoryJson(nullptr, "the renderer was never built", unknownHost);
  for (const char* k :
       {"gpu_bytes", "gpu_total_bytes", "gpu_lod_bytes", "gpu_capture_bytes", "host_peak_bytes", "host_peak_scope"})
    EXPECT_TRUE(m[k].is_null()) << k;
  EXPECT_EQ(m["gpu_reason"], "the renderer was never built");
  EXPECT_EQ(m["host_reason"], "no /proc/self/status");
  // A peak that could not be reset covers the whole process, and says so.
  const json p = memoryJson(nullptr, "x", HostPeak{1 << 20, false, ""});
  EXPECT_EQ(p["host_peak_scope"], "process");
  EXPECT_TRUE(p["host_reason"].is_null());
}

// The report: the equal-error table shows each case's device memory beside its milliseconds (a
// case without a memory record gets the missing mark), and the Memory table one row per case.
TEST(MemoryReport, EqualErrorTableAndMemoryTable) {
  ReportRun run;
  run.context = {{"device", "NVIDIA H100 80GB HBM3"}};
  auto add = [&](const std::string& scheme, json memory) {
    ReportCase c;
    c.id = scheme;
    c.scheme = scheme;
    c.status = "ok";
    c.matched = {{"metric", "err_p95_px"}, {"target", 1.0}, {"param", "p"}, {"value", 1}, {"achieved", 1.0}};
    c.summary = {{"gpu_ms", {{"median", scheme == "cdlod" ? 1.0 : 2.0}, {"p95", 2.5}}}};
    if (!memory.is_null()) c.summary["memory"] = memory;
    run.cases.push_back(c);
  };
  GpuMemoryAccount a;
  a.live[size_t(GpuResource::Heights)] = 3u << 20;
  a.live[size_t(GpuResource::Instances)] = 1u << 20;
  a.live[size_t(GpuResource::Capture)] = 5u << 20;  // apart: not in the total
  add("cdlod", memoryJson(&a, "", HostPeak{100 << 20, true, ""}));
  add("sphere", nullptr);
  const EqualErrorSection eq = equalErrorSection(run);
  ASSERT_TRUE(eq.present);
  const auto& h = eq.table.header;
  const size_t col = size_t(std::find(h.begin(), h.end(), "GPU MiB") - h.begin());
  ASSERT_LT(col, h.size());
  EXPECT_EQ(h[col + 1], "of it LOD MiB");
  ASSERT_EQ(eq.table.rows.size(), 2u);
  EXPECT_EQ(eq.table.rows[0][0].md, "cdlod");
  EXPECT_EQ(eq.table.rows[0][col].md, "4.00");
  EXPECT_EQ(eq.table.rows[0][col + 1].md, "1.00");
  EXPECT_EQ(eq.table.rows[1][col].md, "–");
  const Table t = memoryTable(run);
  ASSERT_EQ(t.rows.size(), 1u);
  const size_t host = size_t(std::find(t.header.begin(), t.header.end(), "host peak MiB") - t.header.begin());
  const size_t capture = size_t(std::find(t.header.begin(), t.header.end(), "capture MiB") - t.header.begin());
  ASSERT_LT(host, t.header.size());
  EXPECT_EQ(t.rows[0][host].md, "100.00");
  EXPECT_EQ(t.rows[0][capture].md, "5.00");
}
