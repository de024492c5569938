#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lb {
// Writes RGBA8 pixels as PNG atomically (temp file + rename). Throws on failure.
void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);
}  // namespace lb
