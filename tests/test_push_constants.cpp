// Push-constant blocks: the size each compiled shader declares (read from its SPIR-V: member
// offsets plus the last member's size) equals the size of the C++ struct that fills it, and fits
// the 128 bytes every Vulkan device offers. The C++ sizes are pinned by static_asserts next to
// the structs; this closes the loop with the GLSL side, which has no static_assert.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/probe.h"
#include "shaders/flip_params.h"
#include "shaders/reduce_params.h"
#include "shaders/shared.h"
#include "vk/resources.h"

namespace {

// The few SPIR-V opcodes, decorations and storage classes the sizes need (SPIR-V spec, 3.x).
enum : uint32_t {
  OpName = 5,
  OpTypeInt = 21,
  OpTypeFloat = 22,
  OpTypeVector = 23,
  OpTypeMatrix = 24,
  OpTypeArray = 28,
  OpTypeStruct = 30,
  OpTypePointer = 32,
  OpConstant = 43,
  OpVariable = 59,
  OpDecorate = 71,
  OpMemberDecorate = 72,
  DecorationArrayStride = 6,
  DecorationMatrixStride = 7,
  DecorationOffset = 35,
  StorageClassPushConstant = 9,
};

struct Module {
  std::map<uint32_t, std::vector<uint32_t>> types;  // id -> the instruction (opcode first)
  std::map<uint32_t, uint32_t> constants, arrayStride, pointee;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> offset, matrixStride;  // (struct, member)
  std::map<uint32_t, std::string> names;
  std::set<uint32_t> pushPointers;  // pointer types of PushConstant variables

  uint32_t size(uint32_t id, uint32_t structId = 0, uint32_t member = 0) const {
    const std::vector<uint32_t>& t = types.at(id);
    switch (t[0]) {
      case OpTypeInt:
      case OpTypeFloat:
        return t[2] / 8;
      case OpTypeVector:
        return t[3] * size(t[2]);
      case OpTypeMatrix:
        return t[3] * matrixStride.at({structId, member});
      case OpTypeArray:
        return constants.at(t[3]) * arrayStride.at(id);
      case OpTypeStruct: {
        uint32_t end = 0;
        for (uint32_t m = 0; m + 2 < t.size(); ++m) end = std::max(end, offset.at({id, m}) + size(t[2 + m], id, m));
        return end;
      }
    }
    throw std::runtime_error("unexpected type in a push-constant block");
  }
};

Module parse(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::vector<uint32_t> w;
  for (uint32_t word; f.read(reinterpret_cast<char*>(&word), 4);) w.push_back(word);
  Module m;
  for (size_t i = 5; i < w.size();) {
    const uint32_t op = w[i] & 0xffff, n = w[i] >> 16;
    const std::vector<uint32_t> ins(w.begin() + long(i), w.begin() + long(i + n));
    i += n;
    if (op == OpName) m.names[ins[1]] = reinterpret_cast<const char*>(&ins[2]);
    if (op >= OpTypeInt && op <= OpTypeStruct) m.types[ins[1]] = {op};
    if (op >= OpTypeInt && op <= OpTypeStruct)
      m.types[ins[1]].insert(m.types[ins[1]].end(), ins.begin() + 1, ins.end());
    if (op == OpConstant) m.constants[ins[2]] = ins[3];
    if (op == OpTypePointer && ins[2] == StorageClassPushConstant) m.pointee[ins[1]] = ins[3];
    if (op == OpVariable && ins[3] == StorageClassPushConstant) m.pushPointers.insert(ins[1]);
    if (op == OpDecorate && ins[2] == DecorationArrayStride) m.arrayStride[ins[1]] = ins[3];
    if (op == OpMemberDecorate && ins[3] == DecorationOffset) m.offset[{ins[1], ins[2]}] = ins[4];
    if (op == OpMemberDecorate && ins[3] == DecorationMatrixStride) m.matrixStride[{ins[1], ins[2]}] = ins[4];
  }
  return m;
}

TEST(PushConstants, EveryShaderBlockHasTheSizeOfItsCppMirror) {
  const std::map<std::string, uint32_t> mirrors = {
      {"DrawPush", uint32_t(sizeof(lb::DrawPush))}, {"ComputePush", uint32_t(sizeof(lb::ComputePush))},
      {"Probe", uint32_t(sizeof(lb::ProbePush))},   {"ReducePush", uint32_t(sizeof(lb::ReducePush))},
      {"FlipPush", uint32_t(sizeof(lb::FlipPush))},
  };
  std::set<std::string> seen;
  for (const auto& entry : std::filesystem::directory_iterator(lb::shaderDir())) {
    if (entry.path().extension() != ".spv") continue;
    const Module m = parse(entry.path().string());
    for (uint32_t pointer : m.pushPointers) {
      const uint32_t block = m.pointee.at(pointer);
      const std::string name = m.names.count(block) ? m.names.at(block) : "?";
      SCOPED_TRACE(entry.path().filename().string() + ": block " + name);
      ASSERT_TRUE(mirrors.count(name)) << "a push-constant block without a C++ mirror listed here";
      EXPECT_EQ(m.size(block), mirrors.at(name));
      EXPECT_LE(m.size(block), uint32_t(LB_PUSH_CONSTANT_LIMIT));
      seen.insert(name);
    }
  }
  EXPECT_EQ(seen.size(), mirrors.size()) << "some mirrored block is in no compiled shader";
}

}  // namespace
