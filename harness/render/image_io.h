#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lb {
// Writes RGBA8 pixels as PNG atomically (temp file + rename), compressed by zlib at kPngZlibLevel;
// RGB when every alpha is 255 (images of people and masks alike are opaque). Throws on failure.
void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

// zlib's default level. On the default job's 488 images (320x180): 30.9 MB in 4.0 s, against 30.2 MB in
// 12.1 s at level 9 and 47.8 MB in 3.4 s for stb's own deflate on RGBA (what this replaced).
constexpr int kPngZlibLevel = 6;
// The RGB bytes of RGBA8 pixels whose alpha is all 255; empty when any pixel is not opaque.
std::vector<uint8_t> opaqueRgb(const uint8_t* rgba, size_t pixels);

// Background of images written for people (run images, `lodbench render`): a light grey-blue sky.
// Measurement renders keep the clear colour pure magenta (metrics/raycast_shade.h kClearRgba),
// which no terrain pixel has: crack detection and the image metrics' "no terrain" mask rely on it.
constexpr std::array<uint8_t, 4> kSkyRgba = {196, 210, 226, 255};

// Nearest-neighbour scaling of RGBA8 or one-byte-per-pixel (mask) images: every output pixel takes
// the source pixel its centre falls in, so a mask measured at a case's resolution marks the same
// places on a larger image of the same frame.
std::vector<uint8_t> scaleNearest(const std::vector<uint8_t>& src, int width, int height, int channels, int outWidth,
                                  int outHeight);
}  // namespace lb
