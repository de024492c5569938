// The task payload of a mesh path whose task shader reads one instance record an invocation (a
// base-grid patch, a selected node: LB_MESH_TASK_RECORDS a workgroup, from DrawPush::firstPatch on,
// DrawPush::count in all): the records that make triangles, compacted, each with its first mesh
// workgroup and two words of what its mesh workgroups need (the scheme's).
struct RecordTask {
  uint record;
  uint firstGroup;
  uint word0, word1;
};
struct RecordPayload {
  uint count;
  RecordTask tasks[LB_MESH_TASK_RECORDS];
};
taskPayloadSharedEXT RecordPayload payload;

#ifdef LB_TASK_SHADER
shared uint groupsOf[LB_MESH_TASK_RECORDS];

// Called by every invocation with its record's mesh workgroups (0: none, or no record); returns
// the workgroup's total, for EmitMeshTasksEXT, after the payload is complete.
uint compactRecords(uint record, uint groups, uint word0, uint word1) {
  uint self = gl_LocalInvocationIndex;
  groupsOf[self] = groups;
  barrier();
  uint slot = 0, first = 0, slots = 0, total = 0;
  for (uint k = 0; k < LB_MESH_TASK_RECORDS; ++k) {
    uint g = groupsOf[k];
    if (k < self) {
      first += g;
      slot += g > 0u ? 1u : 0u;
    }
    total += g;
    slots += g > 0u ? 1u : 0u;
  }
  if (groups > 0u) payload.tasks[slot] = RecordTask(record, first, word0, word1);
  if (self == 0u) payload.count = slots;
  barrier();
  return total;
}
#else
// The record task of this mesh workgroup, and the workgroup's index among that record's.
RecordTask recordTask(out uint group) {
  uint g = gl_WorkGroupID.x, lo = 0u, hi = payload.count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (payload.tasks[mid].firstGroup <= g)
      lo = mid;
    else
      hi = mid - 1u;
  }
  group = g - payload.tasks[lo].firstGroup;
  return payload.tasks[lo];
}
#endif
