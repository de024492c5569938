#pragma once
// What a frame is drawn with and what it yields, as plain data: the render modes, the settings a
// renderer is built with, a frame's timings and counters, and the triangle-size histogram. Metrics
// and results include this header, not the renderer (render/renderer.h), when data is all they need.
#include <array>
#include <cstdint>

#include "terrain/page_layout.h"

namespace lb {

// Shaded/Heatmap/Wireframe write RGBA8 (Wireframe: the shaded frame with the tessellation's edges,
// coloured by level, blended over it); Error writes per-pixel screen-space error (R32F, -1 where
// no terrain); Histogram bins triangle areas in a geometry shader and rasterizes nothing.
// Timing modes (sweep/timing_modes.h): Depth rasterizes into depth only (no colour attachment, no
// fragment shader); Frontend discards every primitive before rasterization, so only the vertex,
// LOD decision (control) and tessellator/evaluation stages run.
enum class RenderMode { Shaded = 0, Heatmap = 1, Wireframe = 2, Error = 3, Histogram = 4, Depth = 5, Frontend = 6 };

// Triangle counts by screen-space area (see LB_HIST_* in shaders/shared.h).
struct TriangleHistogram {
  std::array<uint64_t, 15> bins{};  // < 1/8 px, [1/8, 1/4), ..., [512, 1024), >= 1024 px
  uint64_t offscreen = 0, backfacing = 0;
  uint64_t degenerate = 0;  // of all the above: zero area on the ground plane (LB_HIST_DEGENERATE), not an extra bin
  double areaSum = 0;       // exact sum of the binned (on-screen, front-facing) areas in px^2 (1/256 px^2 steps)
  uint64_t total() const {
    uint64_t t = offscreen + backfacing;
    for (uint64_t b : bins) t += b;
    return t;
  }
};

struct RenderSettings {
  int width = 320, height = 180;
  int grid = 32;  // patches per side
  // Testing only (planted regression, in [0, 1]): timing frames draw the first fraction of every
  // eighth of the patches again, after the statistics query ends and before the closing
  // timestamp, so GPU time grows while the counters stay exact (see Renderer::record).
  double testSlowdown = 0;
  // Images for people: the resolution the LOD decisions, error pixels and histogram
  // areas assume (0 = width x height). A case's images render its frames at more pixels with the
  // case's own tessellation: lodWidth x lodHeight = the case's resolution (same aspect ratio).
  int lodWidth = 0, lodHeight = 0;
  // Clear colour: magenta (kClearRgba) for measurement and timing frames, or the neutral sky
  // (kSkyRgba, render/image_io.h) for images written for people; never sky where cracks are detected.
  bool sky = false;
  // Testing only: shade with the per-pixel normal from four height lookups that came before the
  // normal map (shaders/terrain.frag kHeightNormals); the geometry and counters are the same.
  bool testHeightNormals = false;
  // Testing only: shade from the normal map's level 0 at every distance, as before the mip chain
  // (shaders/terrain.frag kMipZero).
  bool testMipZeroShading = false;
  // Testing only: upload the heights' pages with a planted defect (render/height_pages.h).
  PageDefect testPageDefect = PageDefect::None;
  // Testing only: at most this many pages a page array (0: as many as the device allows), so a
  // small terrain fills several arrays as only the largest do otherwise.
  uint32_t testPageLayers = 0;
  // Testing only: the normal map in pages of this many texels (0: chosen by the terrain's size),
  // at most this many pages an array (0: as the device allows), with a planted defect
  // (render/normal_pages.h), so a small terrain's map is cut as a large one's is.
  int testNormalPageCells = 0;
  uint32_t testNormalPageLayers = 0;
  bool testNormalPageDefect = false;
  // Testing only: with pages, the map's level whose chain is also one image (0: the first that
  // fits, as a map past one image gets; past the map's levels: none, every pixel from the pages).
  int testNormalCoarseFrom = 0;
  // Testing only: the mesh capture holds at most this many triangles (0: what one storage buffer of
  // 2 GiB holds, 44.7 M), so a small frame overflows it as only the largest frames do otherwise.
  uint32_t testMeshCaptureMost = 0;
};

// Counters of the pipeline-statistics query around a frame's terrain draws.
struct PipelineStats {
  uint64_t iaVertices = 0, iaPrimitives = 0, vsInvocations = 0;
  uint64_t tcsPatches = 0, tesInvocations = 0;
  uint64_t clipInvocations = 0, clipPrimitives = 0, fsInvocations = 0;
  // Mesh-shader paths (where the device counts them: meshShaderQueries): task and mesh shader
  // invocations. Those frames count no input assembly, vertex or tessellation work.
  uint64_t taskInvocations = 0, meshInvocations = 0;
};

struct FrameResult {
  int frame = 0;
  double gpuMs = 0;  // timestamps around the terrain draws x timestampPeriod
  double cpuMs = 0;  // host time between consecutive frame submissions
  // The harness's own host cost of the frame: uniform fill, recording, submit, and the read-back
  // of its queries (the fence wait is left out: that is the GPU's time, not the harness's).
  double harnessMs = 0;
  PipelineStats stats;
  // Draw paths whose LOD runs apart from drawing (instanced grid): GPU time of the LOD work and of
  // the draws (GpuSample), and the CPU selection plus its upload (inside harnessMs). -1 = none
  // (tessellation: the LOD decision runs inside the draws).
  double lodMs = -1, drawMs = -1, lodCpuMs = -1;
  uint64_t instances = 0;  // instanced path: instances drawn (all footprints)
  uint32_t draws = 0;      // draw calls of the terrain
};

// Wall seconds of a renderer's load-time work for run.json costs.terrains: the heights cut into
// pages and uploaded, the normal map (both in its constructor) and the last setScheme's
// preprocessing (CPU, or the compute pass, with the upload).
struct SetupCosts {
  double pagesS = 0, normalMapS = 0, preprocessS = 0;
};

// Which camera's frustum the LOD culls with (FrameUniforms::frustum): Lod (default), or View, which
// keeps culling live under a frozen LOD camera so popping (replay/popping.h) sees no culled holes.
enum class CullCamera { Lod, View };

}  // namespace lb
