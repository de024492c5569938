// The GPU ray-cast ground truth (harness/metrics/gpu_raycast.h, shaders/raycast.glsl): bindings and
// sizes shared by the C++ side and the shader.
#ifndef LB_RAYCAST_PARAMS_H
#define LB_RAYCAST_PARAMS_H
#define LB_RAYCAST_BINDING_HEIGHTS 0   // float per heightfield sample, page after page (terrain/page_layout.h)
#define LB_RAYCAST_BINDING_MIP 1       // every max-mipmap level, level 0 first (offsets in the params)
#define LB_RAYCAST_BINDING_NORMALS 2   // the normal map's RG16F texels, one uint each, all levels
#define LB_RAYCAST_BINDING_RGBA 3      // out: uint per pixel, bytes R, G, B, A
#define LB_RAYCAST_BINDING_DISTANCE 4  // out: float per pixel, eye-to-hit distance, -1 on a miss
#define LB_RAYCAST_BINDING_PARAMS 5    // uniform block: camera, terrain, pyramid levels
#define LB_RAYCAST_GROUP 8             // 8 x 8 pixels per workgroup
// Stack entries pack a node as level (4 bits), ix and iz (14 bits each); level-0 cells never go on
// the stack, so a node on it is at level >= 1 and ix, iz < 2^14: at most 32768 cells a side, 16
// levels. The deepest stack: the root, then 3 more per level expanded down to level 2.
#define LB_RAYCAST_MAX_LEVELS 16
#define LB_RAYCAST_MAX_CELLS 32768
#define LB_RAYCAST_STACK 48
#endif
