#include "gpu_fixture.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace lbtest {

lb::Context& gpu() {
  static lb::Context* ctx = [] {
    auto* c = new lb::Context();
    const char* dev = std::getenv("LODBENCH_TEST_DEVICE");
    lb::createContext(*c, {dev ? dev : "", false});
    if (c->validationEnabled) std::fprintf(stderr, "[lodbench tests] Vulkan validation layer enabled\n");
    std::atexit([] { lb::destroyContext(gpu()); });
    return c;
  }();
  return *ctx;
}

const lb::Heightfield& testTerrain() {
  static const lb::Heightfield hf = [] {
    lb::TerrainSpec s;
    s.size = 129;
    s.seed = 7;
    s.extent = 1000;
    s.heightScale = 120;
    return lb::makeProcedural(s);
  }();
  return hf;
}

lb::CameraPose poseAt(glm::vec3 eye, glm::vec3 target, float fov) {
  lb::CameraPose p;
  p.eye = eye;
  p.target = target;
  p.fovDeg = fov;
  return p;
}

lb::CameraPose overviewPose() {
  return poseAt({-200, 600, -200}, {500, 0, 500});
}

lb::FrameResult renderOnce(lb::Renderer& r, const lb::CameraPose& pose) {
  r.submitFrame(0, pose, pose);
  r.finish();
  auto done = r.takeCompleted();
  EXPECT_EQ(done.size(), 1u);
  return done.empty() ? lb::FrameResult{} : done.back();
}

bool drawsOnTestDevice(const lb::Scheme& scheme) {
  return scheme.info().path != lb::DrawPath::Mesh || gpu().meshShader;
}

std::vector<const lb::Scheme*> drawableSchemes() {
  std::vector<const lb::Scheme*> out;
  for (const lb::Scheme* s : lb::allSchemes())
    if (drawsOnTestDevice(*s)) out.push_back(s);
  return out;
}

std::vector<std::string> shippedPathFiles() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths"))
    if (e.path().extension() == ".csv") out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace lbtest
