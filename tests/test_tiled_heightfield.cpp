// The tiled heightfield (docs/tiled-heightfield.md): a terrain cut into pages is the same terrain.
// PageLayout.* check the layout on the host; TiledHeightfield.* draw every scheme the test device
// draws from a 1025 x 769 terrain in pages of 60 cells (18 x 13 pages, the last of a row holding 4
// cells, of a column 48) and from the single image, and require every output bit for bit equal:
// shaded and error images, histograms, pipeline counters, captured levels and meshes, the
// scheme texture and the GPU ray cast. Every figure of a case derives from these and the host array,
// which paging leaves alone. Planted page defects (an origin one sample off, a border left out, a
// table entry at the wrong layer) must change the images. The whole sweep of case files for both
// terrains and both camera paths is TiledHeightfieldSweep.* (heavy).
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
#include "config/config.h"
#include "crop_rows.h"
#include "gpu_fixture.h"
#include "metrics/gpu_raycast.h"
#include "render/renderer.h"
#include "render/terrain_fit.h"
#include "schemes/preprocess/density_map.h"
#include "schemes/registry.h"
#include "sha256.h"
#include "shaders/shared.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"
#include "terrain/page_layout.h"
#include "vk/device_limits.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kPage = 60;

// Procedural 1025^2 cut to 1025 x 769 samples: non-square, and 60 divides neither side's cells.
const Heightfield& wideTerrain() {
  static const Heightfield hf = [] {
    TerrainSpec s;
    s.size = 1025;
    s.seed = 11;
    s.extent = 1000;
    s.heightScale = 150;
    return lbtest::cropRows(makeProcedural(s), 769);
  }();
  return hf;
}

Heightfield paged(const Heightfield& hf, int page) {
  Heightfield p = hf;
  p.page = page;
  return p;
}

// A view over the whole terrain and a low one across many page borders.
std::vector<CameraPose> poses() {
  return {lbtest::poseAt({-150, 420, -150}, {500, 0, 380}), lbtest::poseAt({310, 95, 240}, {620, 30, 520}, 50.0f)};
}

RenderSettings settings() {
  RenderSettings s;
  s.width = 160;
  s.height = 90;
  s.grid = 16;
  return s;
}

// Everything a renderer hands the metrics for one pose, as bytes.
std::vector<uint8_t> outputs(Renderer& r, const CameraPose& pose) {
  std::vector<uint8_t> out;
  auto add = [&out](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    out.insert(out.end(), b, b + n);
  };
  FrameResult fr;  // the heat map is the same geometry in other colours: the shaded image stands for both
  const std::vector<uint8_t> px = r.renderImage(pose, pose, RenderMode::Shaded, &fr);
  add(px.data(), px.size());
  add(&fr.stats, sizeof fr.stats);
  const std::vector<float> levels = r.capturedLevels();
  add(levels.data(), levels.size() * sizeof(float));
  const std::vector<float> error = r.renderErrorMap(pose, pose);
  add(error.data(), error.size() * sizeof(float));
  const TriangleHistogram h = r.measureHistogram(pose, pose);
  add(h.bins.data(), sizeof h.bins);
  const uint64_t rest[3] = {h.offscreen, h.backfacing, h.degenerate};
  add(rest, sizeof rest);
  add(&h.areaSum, sizeof h.areaSum);
  const std::vector<glm::vec3>& mesh = r.capturedMesh();
  add(mesh.data(), mesh.size() * sizeof(glm::vec3));
  return out;
}

class TiledHeightfield : public lbtest::GpuTest {};

}  // namespace

TEST(PageLayout, PagesCoverEverySampleAndShareTheirBorders) {
  const PageLayout one = pageLayout(1025, 769, 0);
  EXPECT_EQ(one.pageCount(), 1);
  EXPECT_EQ(one.storedX(), 1025);
  EXPECT_EQ(one.storedZ(), 769);
  const PageLayout l = pageLayout(1025, 769, kPage);
  EXPECT_EQ(l.pagesX, 18);  // 17 x 60 = 1020 cells, the 18th page holds the last 4
  EXPECT_EQ(l.pagesZ, 13);  // 12 x 60 = 720 cells, the 13th holds 48
  EXPECT_EQ(l.pageOfX(1019), 16);
  EXPECT_EQ(l.pageOfX(1020), 17);
  EXPECT_EQ(l.pageOfX(1024), 17);  // the last sample: the last page's border
  EXPECT_EQ(pageLayout(1025, 1025, 64).pagesX, 16);
  EXPECT_EQ(pageLayout(1025, 1025, 64).pageOfX(1024), 15);  // 1024 = 16 x 64: the border of page 15
  EXPECT_EQ(pageLayout(100, 40, 500).pageCount(), 1);       // a page larger than the terrain: one page
  EXPECT_EQ(pageLayout(100, 40, 500).storedX(), 100);

  // Every stored sample is the host array's sample at its place (clamped past the edge), so a
  // cell's corners read from its page are Heightfield::at's.
  const Heightfield& hf = wideTerrain();
  const UninitVector<float> all = pagedHeights(hf, l);
  ASSERT_EQ(all.size(), l.pageSamples() * size_t(l.pageCount()));
  size_t wrong = 0;
  for (int j = 0; j < l.pagesZ; ++j)
    for (int i = 0; i < l.pagesX; ++i)
      for (int z = 0; z < l.storedZ(); ++z)
        for (int x = 0; x < l.storedX(); ++x) {
          const float stored = all[size_t(j * l.pagesX + i) * l.pageSamples() + size_t(z) * l.storedX() + x];
          const float want = hf.at(i * l.cellsX + x, j * l.cellsZ + z);
          wrong += std::memcmp(&stored, &want, sizeof want) != 0;
        }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(pagedHeights(hf, one), hf.h);  // the one-page case is the host array
}

// Draws each scheme `only` names (every scheme the device draws when empty) from the single image
// and from pages of kPage cells and compares their outputs bit for bit. reference and cbt-ts draw a
// 257 x 193 corner of the terrain (5 x 4 pages, the last of each partly used) on a 2 x 2 grid:
// reference's 64 x 64 quads a patch are slow in lavapipe's geometry shader, and cbt-ts's capture
// bound on the whole terrain passes lavapipe's maxStorageBufferRange.
static void expectPagedDrawsEqual(const std::vector<std::string>& only) {
  const Heightfield& single = wideTerrain();
  Heightfield corner = single;
  corner.width = 257;
  corner.height = 193;
  corner.h.clear();
  for (int z = 0; z < corner.height; ++z)
    corner.h.insert(corner.h.end(), single.h.begin() + ptrdiff_t(z) * single.width,
                    single.h.begin() + ptrdiff_t(z) * single.width + corner.width);
  corner.updateRange();
  size_t schemes = 0;
  for (const Heightfield* terrain : std::vector<const Heightfield*>{&single, &corner}) {
    const Heightfield pages = paged(*terrain, kPage);
    RenderSettings rs = settings();
    if (terrain == &corner) rs.grid = 2;
    Renderer a(lbtest::gpu(), *terrain, rs);
    Renderer b(lbtest::gpu(), pages, rs);
    for (const Scheme* s : lbtest::drawableSchemes()) {
      const std::string& name = s->info().name;
      if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
      if ((name == "reference" || name == "cbt-ts") != (terrain == &corner)) continue;
      a.setScheme(*s, {});
      b.setScheme(*s, {});
      const SchemeTexture ta = a.readSchemeTexture(), tb = b.readSchemeTexture();
      EXPECT_EQ(ta.rgba, tb.rgba) << name << ": scheme texture";
      // The view over the whole terrain reads every page, the partly used last ones included.
      EXPECT_TRUE(outputs(a, poses()[0]) == outputs(b, poses()[0])) << name;
      ++schemes;
    }
  }
  EXPECT_EQ(schemes, only.empty() ? lbtest::drawableSchemes().size() : only.size());
}

// Heavy: every scheme the device draws.
TEST_F(TiledHeightfield, EverySchemeDrawsThePagedTerrainAsTheSingleImage) {
  expectPagedDrawsEqual({});
}

// One scheme of each way heights are read: tessellation, a compute pass (planefit), the instanced
// grid and the GPU-indirect path.
TEST_F(TiledHeightfield, OneSchemeOfEachDrawPathDrawsThePagedTerrainAsTheSingleImage) {
  expectPagedDrawsEqual({"uniform", "planefit", "cdlod", "cbt"});
}

// Pages spread over several page arrays (at most 64 pages an array: 234 pages in 4 arrays, as
// only terrains past the device's layers fill otherwise) draw as one array does: the shaders then
// choose each page's array, where one array lets them read it directly.
TEST_F(TiledHeightfield, PagesInSeveralArraysDrawAsInOne) {
  const Heightfield pages = paged(wideTerrain(), kPage);
  EXPECT_EQ(createHeightPages(lbtest::gpu(), pages, {}, PageDefect::None, 64).arrays.size(), 4u);
  RenderSettings several = settings();
  several.testPageLayers = 64;
  Renderer a(lbtest::gpu(), pages, settings()), b(lbtest::gpu(), pages, several);
  for (const char* name : {"uniform", "planefit", "cdlod", "cbt"}) {
    const Scheme& s = *findScheme(name);
    a.setScheme(s, {});
    b.setScheme(s, {});
    EXPECT_TRUE(outputs(a, poses()[0]) == outputs(b, poses()[0])) << name;
  }
}

// The GPU ray cast reads the heights in the same pages: the same hits, distances and colours.
TEST_F(TiledHeightfield, GpuRayCastOfThePagedTerrainIsTheSingleImages) {
  const Heightfield& single = wideTerrain();
  const Heightfield pages = paged(single, kPage);
  GpuRaycast a(lbtest::gpu(), single), b(lbtest::gpu(), pages);
  for (const CameraPose& pose : poses()) {
    std::vector<float> da, db;
    const RgbaImage ia = a.image(pose, 160, 90, &da), ib = b.image(pose, 160, 90, &db);
    EXPECT_EQ(ia.px, ib.px);
    EXPECT_EQ(da, db);
    size_t hits = 0;
    for (float d : da) hits += d >= 0;
    EXPECT_GT(hits, da.size() / 4);  // the views see terrain, not only sky
  }
}

// Each planted defect of the pages changes what is drawn: the comparison above would see it.
TEST_F(TiledHeightfield, PlantedPageDefectsChangeTheImages) {
  const Heightfield& single = wideTerrain();
  const Heightfield pages = paged(single, kPage);
  const Scheme& uniform = *findScheme("uniform");
  Renderer good(lbtest::gpu(), pages, settings());
  good.setScheme(uniform, {});
  const std::vector<uint8_t> want = outputs(good, poses()[1]);
  for (PageDefect d : {PageDefect::OriginOffByOne, PageDefect::BorderLeftOut, PageDefect::WrongLayer}) {
    RenderSettings s = settings();
    s.testPageDefect = d;
    Renderer bad(lbtest::gpu(), pages, s);
    bad.setScheme(uniform, {});
    EXPECT_FALSE(outputs(bad, poses()[1]) == want) << "defect " << int(d) << " went unseen";
  }
}

// The memory account tags every page and the table as heights: at least the pages' bytes.
TEST_F(TiledHeightfield, PagesAndTableAreChargedAsHeights) {
  const Heightfield pages = paged(wideTerrain(), kPage);
  Renderer r(lbtest::gpu(), pages, settings());
  const PageLayout l = pageLayout(pages);
  const uint64_t pageBytes = uint64_t(l.pageSamples()) * l.pageCount() * sizeof(float);
  const uint64_t tableBytes = sizeof(HeightTableHeader) + uint64_t(l.pageCount()) * 4;
  EXPECT_GE(r.gpuMemory().bytes(GpuResource::Heights), pageBytes + tableBytes);
  EXPECT_LT(r.gpuMemory().bytes(GpuResource::Heights), 2 * (pageBytes + tableBytes));
}

// An H100's figures (vk/device_limits.h): maxImageDimension2D 32768, 2048 layers, 4 GiB allocations.
DeviceLimits h100() {
  DeviceLimits d;
  d.name = "h100";
  d.maxImageDimension2D = 32768;
  d.maxImageArrayLayers = 2048;
  d.maxAllocationBytes = 4ull << 30;
  d.deviceHeapBytes = 80ull << 30;
  d.stagingHeapBytes = 64ull << 30;
  return d;
}

TEST(TiledLimits, PagesAreBoundByMemoryAndArraysNotOneImage) {
  DeviceLimits d = h100();
  // One page: the single image's limit, word for word.
  EXPECT_EQ(tiledLimitProblem(d, 40000, 40000, 0), terrainLimitProblem(d, 40000, 40000));
  EXPECT_EQ(tiledLimitProblem(d, 32759, 32759, 1023), "");
  // Past one image's side: the normal map is in pages too, so 65537^2 fits the H100's memory.
  EXPECT_EQ(tiledLimitProblem(d, 65537, 65537, 1023), "");
  // A page larger than an image side.
  EXPECT_NE(tiledLimitProblem(d, 40001, 3, 40000).find("pages of 40000 cells"), std::string::npos);
  // Few layers an array: more arrays than the shaders bind.
  d.maxImageArrayLayers = 4;
  const std::string arrays = tiledLimitProblem(d, 8193, 8193, 255);  // 32 x 32 pages in 4-layer arrays
  EXPECT_NE(arrays.find("page arrays"), std::string::npos) << arrays;
  // A small heap: the pages' bytes count against it.
  d = h100();
  d.deviceHeapBytes = 1ull << 30;
  const std::string heap = tiledLimitProblem(d, 16385, 16385, 1023);
  EXPECT_NE(heap.find("memory heap (height pages"), std::string::npos) << heap;
  EXPECT_NE(heap.find("normal map pages"), std::string::npos) << heap;
  EXPECT_LT(largestSquareTiledTerrain(d, 1023), 16385);
  EXPECT_GT(largestSquareTiledTerrain(d, 1023), 8192);
}

namespace {

// A case file without what may differ between two runs of the same frames: times, rates, costs,
// memory (the pages' own bytes), and the names and digests of the terrain's inputs.
json comparable(json j) {
  if (j.is_object()) {
    json out = json::object();
    for (auto& [k, v] : j.items()) {
      const bool timed = (k.size() > 3 && k.compare(k.size() - 3, 3, "_ms") == 0) ||
                         (k.size() > 2 && k.compare(k.size() - 2, 2, "_s") == 0) || k.rfind("fps", 0) == 0;
      static const std::set<std::string> kVolatile = {"seconds", "digest",          "case_id",     "inputs",
                                                      "terrain", "memory",          "calibration", "energy_reason",
                                                      "path",    "measure_costs_ms"};
      if (!timed && !kVolatile.count(k)) out[k] = comparable(v);
    }
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (auto& v : j) out.push_back(comparable(v));
    return out;
  }
  return j;
}

// Case files and image pixels of a run, keyed by case id without the terrain's "-pN".
std::map<std::string, json> runFiles(const fs::path& dir, const std::string& pageTag) {
  std::map<std::string, json> out;
  auto key = [&](std::string name) {
    const size_t at = pageTag.empty() ? std::string::npos : name.find(pageTag);
    if (at != std::string::npos) name.erase(at, pageTag.size());
    return name;
  };
  for (const auto& e : fs::directory_iterator(dir / "cases")) {
    std::ifstream f(e.path());
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    for (size_t at; !pageTag.empty() && (at = text.find(pageTag)) != std::string::npos;) text.erase(at, pageTag.size());
    out[key(e.path().filename().string())] = comparable(json::parse(text));  // image names lose the tag too
  }
  for (const auto& e : fs::directory_iterator(dir / "images")) {
    std::ifstream f(e.path(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    int w = 0, h = 0, n = 0;
    unsigned char* px =
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h, &n, 4);
    if (!px) {
      ADD_FAILURE() << "cannot read " << e.path();
      continue;
    }
    Sha256 s;
    s.update(px, size_t(w) * size_t(h) * 4);
    stbi_image_free(px);
    out["image " + key(e.path().filename().string())] = s.hex();
  }
  return out;
}

// The JSON path of the first difference, for the failure message.
std::string firstDifference(const json& a, const json& b, const std::string& at = "") {
  if (a.type() != b.type()) return at;
  if (a.is_object()) {
    for (auto& [k, v] : a.items()) {
      if (!b.contains(k)) return at + "/" + k;
      const std::string d = firstDifference(v, b[k], at + "/" + k);
      if (!d.empty()) return d;
    }
    return a.size() == b.size() ? "" : at + " (keys)";
  }
  if (a.is_array()) {
    if (a.size() != b.size()) return at + " (length)";
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string d = firstDifference(a[i], b[i], at + "/" + std::to_string(i));
      if (!d.empty()) return d;
    }
    return "";
  }
  return a == b ? "" : at;
}

}  // namespace

// Heavy: the whole measurement pipeline. One scheme of each way heights are read (as above) on the
// flyover and the dive, 4 frames each, every frame measured (histogram, error, image, cracks,
// popping, FLIP), images of the first and last frame in three modes, on 1025 x 769 in pages of 60
// (which divides neither side): every case file equals the single image's but for times and
// memory, and every image's pixels are equal. TiledHeightfield.EverySchemeDraws... covers every
// scheme's renders.
TEST(TiledHeightfieldSweep, CaseFilesAndImagesOfPagedTerrainsEqualTheSingleImages) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("lodbench_tiled_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Heightfield& wide = wideTerrain();
  {
    std::ofstream raw(dir / "wide.r32f", std::ios::binary);
    raw.write(reinterpret_cast<const char*>(wide.h.data()), std::streamsize(wide.h.size() * sizeof(float)));
  }
  std::map<std::string, json> runs[2];
  for (int p = 0; p < 2; ++p) {
    json terrain = {
        {"type", "r32f"}, {"file", (dir / "wide.r32f").string()}, {"width", 1025}, {"height", 769}, {"extent", 1000}};
    if (p == 1) terrain["page"] = kPage;
    json cfg = {{"name", "tiled"},
                {"resolution", {160, 90}},
                {"grid", 16},
                {"fps", 8},
                {"max_frames", 4},
                {"warmup_frames", 0},
                {"repetitions", 1},
                {"terrain", terrain},
                {"paths", {"paths/flyover.csv", "paths/dive.csv"}},
                {"schemes", {"uniform", "planefit", "cdlod", "cbt"}},
                {"measure", {{"every", 1}}},
                {"images", {{"frames", {0, -1}}, {"modes", {"shaded", "heatmap", "error"}}, {"worst", false}}}};
    Config c = parseConfig(cfg.dump(), "tiled.json", std::string(LODBENCH_SOURCE_DIR) + "/configs");
    RunOptions o;
    o.outDir = (dir / ("run" + std::to_string(p))).string();
    o.progress = false;
    RunTotals totals = runSweep(c, o);
    EXPECT_EQ(totals.failed, 0);
    EXPECT_EQ(totals.ok, 8);
    runs[p] = runFiles(o.outDir, p == 1 ? "-p" + std::to_string(kPage) : "");
  }
  ASSERT_EQ(runs[0].size(), runs[1].size());
  EXPECT_EQ(runs[0].size(), 8u + 8u * 2u * 3u);  // case files, and two frames in three modes
  for (auto& [name, want] : runs[0]) {
    ASSERT_TRUE(runs[1].count(name)) << name;
    EXPECT_EQ(firstDifference(want, runs[1][name]), "") << name << " differs, paged by " << kPage;
  }
  fs::remove_all(dir);
}

// `lodbench devices` states the tiled limit beside the single image's.
TEST(TiledLimits, DevicesCommandPrintsTheTiledLimit) {
  const DeviceLimits d = deviceLimits(lbtest::gpu().physicalDevice);
  const std::string side = std::to_string(largestSquareTiledTerrain(d, 1023));
  const lb::test::CliOut o = lb::test::lodbench("devices", false);
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find("largest terrain in pages of 1023 cells: " + side + " x " + side + " samples"),
            std::string::npos)
      << o.text;
}

// A per-sample map (density's, phong's) lives in the heights' pages: read back from pages spread
// over four arrays it is densityMap's floats, and both schemes draw the paged terrain as the single
// image. Before, the map was one image of the terrain's size, which a terrain past one image cannot be.
TEST_F(TiledHeightfield, PerSampleMapsInPagesAreTheHostMapAndDrawAsTheSingleImage) {
  const Heightfield& single = wideTerrain();
  const Heightfield pages = paged(single, kPage);
  RenderSettings several = settings();
  several.testPageLayers = 64;  // 234 pages in 4 arrays
  Renderer a(lbtest::gpu(), single, settings()), b(lbtest::gpu(), pages, several);
  for (const char* name : {"density", "phong"}) {
    const Scheme& s = *findScheme(name);
    const ParamValues params{{"threshold", 0.001}, {"scale", 30.0}};
    a.setScheme(s, params);
    b.setScheme(s, params);
    const std::vector<float> want = densityMap(single, 0.001f, 30.0f);
    const SchemeTexture ta = a.readSchemeTexture(), tb = b.readSchemeTexture();
    EXPECT_EQ(ta.rgba, want) << name;
    EXPECT_EQ(tb.rgba, want) << name;
    // The densities vary: a map of one value would pass the equality above with a wrong layout.
    EXPECT_GT(std::set<float>(want.begin(), want.end()).size(), 1000u);
    for (const CameraPose& pose : poses()) EXPECT_TRUE(outputs(a, pose) == outputs(b, pose)) << name;
  }
}
