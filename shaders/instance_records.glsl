// The instance records of the instanced, GPU-indirect and mesh paths (render/instanced.h
// InstanceRecord): two vec4 a record, whose meaning belongs to the scheme (or, on the mesh path's
// patches, the patch's four corners).
#ifndef LB_INSTANCE_RECORDS_GLSL
#define LB_INSTANCE_RECORDS_GLSL
#include "shared.h"

struct InstanceRecord {
  vec4 a;
  vec4 b;
};
layout(set = 0, binding = LB_BINDING_INSTANCES, std430) readonly buffer Instances { InstanceRecord records[]; }
instances;

#endif
