// Shared by triangle tessellation-control shaders (Topology::Tri3): pass-through, grid vertices of
// the control points, factor output/capture. Include after common.glsl.
layout(vertices = 3) out;
layout(location = 0) in vec3 inPos[];
layout(location = 0) out vec3 outPos[];

layout(constant_id = 1) const bool kCapture = false;
layout(set = 0, binding = LB_BINDING_CAPTURE, std430) buffer Capture { float levels[]; } capture;

uint patchIndex() { return draw.firstPatch + uint(gl_PrimitiveID); }

void passThrough() { outPos[gl_InvocationID] = inPos[gl_InvocationID]; }

// Grid vertex (i, j) of control point k: patch 2q + t is triangle t of quad q = j * N + i, with
// corners (00, 10, 11) for t = 0 and (00, 11, 01) for t = 1 (render/patch_grid.cpp).
ivec2 triGridVertex(int k) {
  int p = int(patchIndex());
  int n = int(frame.terrain.y);
  int q = p / 2;
  ivec2 base = ivec2(q % n, q / n);
  ivec2 offsets0[3] = ivec2[3](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1));
  ivec2 offsets1[3] = ivec2[3](ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
  return base + ((p & 1) == 0 ? offsets0[k] : offsets1[k]);
}

// outer[k] is the edge opposite control point k (Vulkan's u = 0, v = 0, w = 0 edges). The capture
// keeps the quad layout's slots: outer at 0..2, inner at 4 (so "slot 4 == 0" means culled for both).
void writeTriLevels(vec3 outer, float inner) {
  gl_TessLevelOuter[0] = outer.x;
  gl_TessLevelOuter[1] = outer.y;
  gl_TessLevelOuter[2] = outer.z;
  gl_TessLevelInner[0] = inner;
  if (kCapture) {
    uint base = patchIndex() * LB_CAPTURE_STRIDE;
    capture.levels[base + 0] = outer.x;
    capture.levels[base + 1] = outer.y;
    capture.levels[base + 2] = outer.z;
    capture.levels[base + 4] = inner;
  }
}
