// Shared by quad tessellation-control shaders: pass-through, patch culling, factor output/capture.
layout(vertices = 4) out;
layout(location = 0) in vec3 inPos[];
layout(location = 0) out vec3 outPos[];

layout(constant_id = 1) const bool kCapture = false;
layout(set = 0, binding = LB_BINDING_PATCH_BOUNDS, std430) readonly buffer PatchBounds { vec2 bounds[]; } patchBounds;
layout(set = 0, binding = LB_BINDING_CAPTURE, std430) buffer Capture { float levels[]; } capture;

uint patchIndex() { return draw.firstPatch + uint(gl_PrimitiveID); }

void passThrough() { outPos[gl_InvocationID] = inPos[gl_InvocationID]; }

// Patch box from its corner xz and its precomputed height range (the interior can rise above the corners).
bool patchCulled() {
  vec2 hb = patchBounds.bounds[patchIndex()];
  vec2 lo = min(min(inPos[0].xz, inPos[1].xz), min(inPos[2].xz, inPos[3].xz));
  vec2 hi = max(max(inPos[0].xz, inPos[1].xz), max(inPos[2].xz, inPos[3].xz));
  return boxOutsideFrustum(vec3(lo.x, hb.x, lo.y), vec3(hi.x, hb.y, hi.y));
}

// outer: edges u=0 (c0-c3), v=0 (c0-c1), u=1 (c1-c2), v=1 (c3-c2) in Vulkan's quad-domain order.
void writeLevels(vec4 outer, vec2 inner) {
  gl_TessLevelOuter[0] = outer.x;
  gl_TessLevelOuter[1] = outer.y;
  gl_TessLevelOuter[2] = outer.z;
  gl_TessLevelOuter[3] = outer.w;
  gl_TessLevelInner[0] = inner.x;
  gl_TessLevelInner[1] = inner.y;
  if (kCapture) {
    uint base = patchIndex() * LB_CAPTURE_STRIDE;
    capture.levels[base + 0] = outer.x;
    capture.levels[base + 1] = outer.y;
    capture.levels[base + 2] = outer.z;
    capture.levels[base + 3] = outer.w;
    capture.levels[base + 4] = inner.x;
    capture.levels[base + 5] = inner.y;
  }
}
