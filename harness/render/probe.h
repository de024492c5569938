#pragma once
// `lodbench probe`: the minimal tessellation loop (or its instanced twin, ProbeOptions::instanced). One VS/TCS/TES(/FS)
// pipeline with a constant-colour fragment shader, the base grid, one uniform level, one camera: nothing else (no
// uniform buffer, no LOD decision, no shading). Timed with the renderer's GpuProfiler, so its GPU time is the floor
// lodbench's own frame is compared against.
#include <string>
#include <vector>

#include "camera/camera_path.h"
#include "render/frame_data.h"

namespace lb {

struct Context;
struct Heightfield;

struct ProbeOptions {
  int width = 320, height = 180, grid = 32;
  float level = 1;
  RenderMode mode = RenderMode::Shaded;  // Shaded (constant colour), Depth or Frontend
  int warmup = 20, frames = 100;
  // Split draws like the renderer (kMaxVerticesPerDraw / kMaxIndicesPerDraw); needed on lavapipe,
  // whose tessellator indices are 16-bit. Elsewhere the probe draws every patch in one call.
  bool split = true;
  // Attribution variant: the vertex shader fetches each control point's height and the control
  // points travel as vec3, as in lodbench's terrain.vert (its LOD decisions need the heights).
  bool vertexHeight = false;
  // The instanced minimal loop: the same triangles pre-tessellated in one patch-sized footprint and
  // drawn grid^2 times in one instanced draw (shaders/probe_instanced.vert); no tessellation stage.
  bool instanced = false;
};

struct ProbeResult {
  std::vector<double> gpuMs;  // per timed frame
  double medianMs = 0;
  PipelineStats stats;  // of the last frame
  uint32_t draws = 0;
};

// Mirror of the Probe push-constant block of shaders/probe.glsl (std430; checked against the
// SPIR-V by tests/test_push_constants.cpp).
struct ProbePush {
  glm::mat4 viewProj;
  glm::vec4 terrain;  // extent, level, grid (instanced loop)
};
static_assert(sizeof(ProbePush) == 64 + 16 && sizeof(ProbePush) <= 128, "push constant mirror within Vulkan's minimum");

ProbeResult runProbe(Context& ctx, const Heightfield& terrain, const CameraPose& pose, const ProbeOptions& options);
// True where the renderer's draw limits apply (Mesa lavapipe).
bool probeNeedsSplit(const Context& ctx);

}  // namespace lb
