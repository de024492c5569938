// Constants and the frame uniform block, shared by C++ and GLSL (one source of truth).
#ifndef LODBENCH_SHARED_H
#define LODBENCH_SHARED_H

#define LB_BINDING_FRAME 0          // FrameUniforms, dynamic uniform buffer
#define LB_BINDING_HEIGHT 1         // heightfield pages: LB_HEIGHT_ARRAYS R32F 2D array images (heights.glsl)
#define LB_BINDING_SCHEME_TEX 2     // scheme preprocessing output (density map, plane-fit lookup), RGBA32F
#define LB_BINDING_PATCH_BOUNDS 3   // per-patch (minHeight, maxHeight) for culling
#define LB_BINDING_CAPTURE 4        // factor capture: per patch 4 outer + 2 inner levels (measurement passes)
#define LB_BINDING_SCHEME_BUF 5     // scheme storage buffer (e.g. tile adjacency)
#define LB_BINDING_HISTOGRAM 7      // triangle-size histogram (measurement pass)
#define LB_BINDING_SCHEME_IMAGE 6   // compute preprocessing only: the scheme texture as a storage image
#define LB_BINDING_NORMAL 8         // terrain normal map, RG16F gradients, all mips (terrain/normal_map.h)
#define LB_BINDING_INSTANCES 9      // instanced-grid path: InstanceRecord per instance (render/instanced.h)
#define LB_BINDING_MESH 10          // measurement pass: captured triangles of the instanced path (analytic cracks)
#define LB_BINDING_LOD_STATE 11     // GPU-indirect path: the LOD state the compute passes keep across frames
#define LB_BINDING_LOD_ARGS 12      // GPU-indirect path: VkDrawIndexedIndirectCommand the passes write
#define LB_BINDING_MESH_TABLE 13    // mesh path: the tessellation patterns' strip table (tess_piece.h)
#define LB_BINDING_HEIGHT_TABLE 14  // heightfield pages: HeightTableHeader, then one entry per page
#define LB_BINDING_NORMAL_TABLE 15  // normal map pages: a header, then one ivec4 per level (normals.glsl)
#define LB_BINDING_NORMAL_PAGES 16  // normal map pages: LB_NORMAL_ARRAYS RG16F 2D array images (normals.glsl)
#define LB_BINDING_SAMPLE_MAP 17    // a scheme's per-sample map in the heights' pages (sample_map.glsl)

// The heightfield's pages (terrain/page_layout.h, docs/tiled-heightfield.md): a descriptor array of
// this many page arrays (those a terrain does not need repeat the first), and per page one table
// entry: its layer, its array, its level (0 while fully resident) and a not-resident bit, room kept
// for streaming.
#define LB_HEIGHT_ARRAYS 8
// Specialization constant: the page arrays a terrain fills (1 up to LB_HEIGHT_ARRAYS; a pipeline
// without it reads as though all were filled). At 1 the height reads take the array directly:
// llvmpipe runs every case of a switch over the arrays, which cost lavapipe 1.7x its time a frame.
#define LB_SPEC_HEIGHT_ARRAYS 16
// The normal map's pages (terrain/normal_page_layout.h): as many arrays, and their count as a
// specialization constant, for the same reasons.
#define LB_NORMAL_ARRAYS 8
#define LB_SPEC_NORMAL_ARRAYS 17
#define LB_PAGE_LAYER_MASK 0x7ffu  // bits 0-10: layer in its array (maxImageArrayLayers is 2048 on the H100)
#define LB_PAGE_ARRAY_SHIFT 11     // bits 11-14: array
#define LB_PAGE_ARRAY_MASK 0xfu
#define LB_PAGE_LEVEL_SHIFT 15  // bits 15-19: level
#define LB_PAGE_NOT_RESIDENT 0x80000000u

#define LB_MAX_FACTOR 64.0
#define LB_CAPTURE_STRIDE 8      // floats per patch in the capture buffer
#define LB_SCHEME_PARAM_VEC4S 4  // up to 16 scheme parameters, at the slots of shaders/<scheme>_params.h
#define LB_PLANE_FIT_BLOCK 16    // planefit: heightfield samples per block side (ch9 Listing 9.10 numthreads)

#define LB_MODE_SHADED 0
#define LB_MODE_HEATMAP 1
#define LB_MODE_WIREFRAME 2
#define LB_MODE_ERROR 3  // R32F target: screen-space geometric error in pixels
// The modes below reach terrain.frag never or only with rasterization discarded; they are listed
// so that lb::RenderMode (render/frame_data.h) is checked against every value.
#define LB_MODE_HISTOGRAM 4
#define LB_MODE_DEPTH 5
#define LB_MODE_FRONTEND 6

// Mesh path: the records (patches, selected nodes) one task workgroup reads, one an invocation;
// the NVIDIA H100's preferred task and mesh workgroup size (maxPreferred*WorkGroupInvocations).
#define LB_MESH_TASK_RECORDS 32
#ifndef LB_MESH_THREADS
#define LB_MESH_THREADS 32
#endif

// Push-constant blocks must fit the smallest maxPushConstantsSize Vulkan guarantees.
#define LB_PUSH_CONSTANT_LIMIT 128

// Triangle-size histogram: bin 0 is area < 1/8 px, bin k (1..13) is [2^(k-4), 2^(k-3)) px,
// bin 14 is >= 1024 px; then off-screen (outside the frustum or crossing the near plane) and
// back-facing triangles, which are not binned.
#define LB_HIST_BINS 15
#define LB_HIST_OFFSCREEN 15
#define LB_HIST_BACKFACING 16
#define LB_HIST_AREA_LO 17  // exact sum of binned areas in 1/256 px^2, as a 64-bit pair
#define LB_HIST_AREA_HI 18
#define LB_HIST_AREA_SCALE 256.0
// Triangles of zero area on the ground plane (two equal x,z or three on one axis-parallel line:
// morph collapses, degenerate strips, clamped border slivers), counted beside the bins above, so
// the bins and their sum are those of every triangle as before.
#define LB_HIST_DEGENERATE 19
#define LB_HIST_COUNTERS 20

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace lb {
// std140: every member is a vec4 or mat4, so the C++ layout matches without padding rules.
struct FrameUniforms {
  glm::mat4 viewProj;  // projection camera
  glm::mat4 lodView;   // LOD camera (equals the projection camera except in popping passes)
  glm::mat4 lodProj;
  glm::vec4 lodEye;      // xyz: LOD camera position
  glm::vec4 frustum[6];  // culling frustum planes (xyz normal inside, w), world space: the LOD camera's, or
                         // the projection camera's (Renderer::setCullCamera)
  glm::vec4 viewport;    // width, height, 1/width, 1/height in pixels
  glm::vec4 terrain;     // extent, grid patches per side, heightfield width, heightfield height
  glm::vec4 light;       // xyz: direction towards the light
  glm::vec4 params[LB_SCHEME_PARAM_VEC4S];
  glm::vec4 origin;   // xy: world x, z of heightfield sample (0, 0) (Heightfield::originX/Z); zw unused
  glm::vec4 shading;  // xyz: the view camera's position; w: one pixel's angle (shaders/footprint.h)
};
static_assert(sizeof(FrameUniforms) == 3 * 64 + 16 + 6 * 16 + 3 * 16 + LB_SCHEME_PARAM_VEC4S * 16 + 2 * 16,
              "std140 mirror");
// Each push-constant mirror is pinned to its GLSL block's size (std430, as push constants are
// laid out); tests/test_push_constants.cpp reads the same sizes back from the compiled SPIR-V.
struct DrawPush {
  uint32_t firstPatch;  // gl_PrimitiveID restarts at every split draw; mesh path: the draw's first record
  uint32_t count;       // mesh path: the records from firstPatch on that the draw's task shader reads
};
static_assert(sizeof(DrawPush) == 8 && sizeof(DrawPush) <= LB_PUSH_CONSTANT_LIMIT, "push constant mirror");
// Push constants of a scheme's compute preprocessing pass (shaders/*.comp define LB_COMPUTE_PASS).
struct ComputePush {
  glm::vec4 terrain;                        // extent, grid patches per side, heightfield min height, max height
  glm::vec4 params[LB_SCHEME_PARAM_VEC4S];  // the scheme's parameters, packed as in FrameUniforms
};
static_assert(sizeof(ComputePush) == 16 + LB_SCHEME_PARAM_VEC4S * 16 && sizeof(ComputePush) <= LB_PUSH_CONSTANT_LIMIT,
              "push constant mirror");
// The head of the page table buffer (std430, shaders/heights.glsl HeightTable); the entries follow.
struct HeightTableHeader {
  int32_t samples[4];  // the terrain's samples along x and z; cells a page holds along x and z
  int32_t pages[4];    // pages along x and z; unused
};
static_assert(sizeof(HeightTableHeader) == 32, "std430 mirror");
}  // namespace lb
#elif defined(LB_COMPUTE_PASS)
layout(push_constant) uniform ComputePush {
  vec4 terrain;
  vec4 params[LB_SCHEME_PARAM_VEC4S];
}
pass;
#else
layout(set = 0, binding = LB_BINDING_FRAME, std140) uniform FrameUniforms {
  mat4 viewProj;
  mat4 lodView;
  mat4 lodProj;
  vec4 lodEye;
  vec4 frustum[6];
  vec4 viewport;
  vec4 terrain;
  vec4 light;
  vec4 params[LB_SCHEME_PARAM_VEC4S];
  vec4 origin;
  vec4 shading;
}
frame;
layout(push_constant) uniform DrawPush {
  uint firstPatch;
  uint count;
}
draw;
#endif

#endif
