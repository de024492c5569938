#pragma once
// The colour spaces FLIP's colour pipeline passes through (metrics/flip.h): sRGB, linear RGB, CIE
// XYZ (D65), the opponent space YCxCz (linear in XYZ, so filters act on it as on light) and
// Hunt-adjusted CIE L*a*b*, with the HyAB distance. The GPU passes (shaders/flip_common.glsl) use the
// same matrices.
#include <array>
#include <cmath>

namespace lb {

using Color3 = std::array<double, 3>;

// sRGB primaries, D65 white (IEC 61966-2-1): linear RGB to XYZ and back.
constexpr double kRgbToXyz[3][3] = {
    {0.4124564, 0.3575761, 0.1804375}, {0.2126729, 0.7151522, 0.0721750}, {0.0193339, 0.1191920, 0.9503041}};
constexpr double kXyzToRgb[3][3] = {
    {3.2404542, -1.5371385, -0.4985314}, {-0.9692660, 1.8760108, 0.0415560}, {0.0556434, -0.2040259, 1.0572252}};
// The white point: XYZ of linear RGB (1, 1, 1).
constexpr Color3 kWhiteXyz = {kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
                              kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
                              kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

inline double srgbToLinear(int byte) {
  double c = double(byte) / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

inline Color3 multiply(const double (&m)[3][3], const Color3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}
inline Color3 linearRgbToXyz(const Color3& rgb) {
  return multiply(kRgbToXyz, rgb);
}
inline Color3 xyzToLinearRgb(const Color3& xyz) {
  return multiply(kXyzToRgb, xyz);
}

// YCxCz: Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
inline Color3 xyzToYcxcz(const Color3& xyz) {
  double x = xyz[0] / kWhiteXyz[0], y = xyz[1] / kWhiteXyz[1], z = xyz[2] / kWhiteXyz[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}
inline Color3 ycxczToXyz(const Color3& o) {
  double y = (o[0] + 16.0) / 116.0, x = o[1] / 500.0 + y, z = y - o[2] / 200.0;
  return {x * kWhiteXyz[0], y * kWhiteXyz[1], z * kWhiteXyz[2]};
}

// CIE L*a*b* with the Hunt adjustment of FLIP: a* and b* scaled by 0.01 L* (colour differences
// are less visible in the dark).
inline Color3 huntLab(const Color3& xyz) {
  auto f = [](double t) {
    const double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  double fx = f(xyz[0] / kWhiteXyz[0]), fy = f(xyz[1] / kWhiteXyz[1]), fz = f(xyz[2] / kWhiteXyz[2]);
  double l = 116.0 * fy - 16.0;
  return {l, 0.01 * l * 500.0 * (fx - fy), 0.01 * l * 200.0 * (fy - fz)};
}

// HyAB: the lightness difference as a city-block term, the chroma difference as a Euclidean one.
inline double hyab(const Color3& a, const Color3& b) {
  return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// One pixel's FLIP from both images' Hunt-adjusted L*a*b* and detector magnitudes (metrics/flip.cpp).
double flipPixel(const Color3& labRef, const Color3& labTest, double edgeRef, double edgeTest, double pointRef,
                 double pointTest, double cmax);

}  // namespace lb
