#include "metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <stdexcept>

#include "metrics/flip_color.h"
#include "render/image_io.h"
#include "stats.h"

namespace lb {

namespace {

const double kPi = 3.14159265358979323846;

// The contrast-sensitivity function of one channel as a sum of two Gaussians in the spatial domain,
// a sqrt(pi / b) exp(-pi^2 x^2 / b), x in degrees (the paper's Table 1).
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
constexpr Csf kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
constexpr Csf kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};

// One Gaussian term of a CSF sampled at whole pixels, unnormalised.
std::vector<double> csfTerm(double a, double b, int r, double ppd) {
  std::vector<double> k(size_t(2 * r + 1));
  for (int i = -r; i <= r; ++i) {
    double x = double(i) / ppd;
    k[size_t(i + r)] = a * std::sqrt(kPi / b) * std::exp(-kPi * kPi * x * x / b);
  }
  return k;
}

double sum(const std::vector<double>& k) {
  double s = 0;
  for (double v : k) s += v;
  return s;
}

std::vector<double> normalised(std::vector<double> k) {
  double s = sum(k);
  for (double& v : k) v /= s;
  return k;
}

// Positive taps scaled to sum 1, negative ones to sum -1 (the detectors respond alike to either sign).
std::vector<double> signNormalised(std::vector<double> k) {
  double pos = 0, neg = 0;
  for (double v : k) (v > 0 ? pos : neg) += v;
  for (double& v : k) v = v > 0 ? v / pos : (v < 0 ? v / -neg : 0);
  return k;
}

}  // namespace

FlipKernels flipKernels(double ppd) {
  if (!(ppd > 0) || !std::isfinite(ppd)) throw std::invalid_argument("FLIP needs a positive pixels-per-degree");
  FlipKernels k;
  k.ppd = ppd;
  // One radius for every channel: three standard deviations of the widest Gaussian (b = 0.04).
  double bMax = 0;
  for (const Csf& c : {kCsfAchromatic, kCsfRedGreen, kCsfBlueYellow}) bMax = std::max({bMax, c.b1, c.b2});
  const int r = int(std::ceil(3.0 * std::sqrt(bMax / (2.0 * kPi * kPi)) * ppd));
  k.csfRadius = r;
  // The 2D kernels are products of 1D Gaussians (the second terms of A and RG have a = 0), so each
  // filters separably; BY's two terms keep their shares of the 2D sum, each 1D term's sum squared.
  k.achromatic = normalised(csfTerm(kCsfAchromatic.a1, kCsfAchromatic.b1, r, ppd));
  k.redGreen = normalised(csfTerm(kCsfRedGreen.a1, kCsfRedGreen.b1, r, ppd));
  std::vector<double> by1 = csfTerm(kCsfBlueYellow.a1, kCsfBlueYellow.b1, r, ppd);
  std::vector<double> by2 = csfTerm(kCsfBlueYellow.a2, kCsfBlueYellow.b2, r, ppd);
  // A Gaussian a sqrt(pi/b) g(x) g(y): its 2D sum is (a sqrt(pi/b)) x (sum of g)^2 = (sum of the 1D term)^2 / (a
  // sqrt(pi/b)).
  double w1 = std::pow(sum(by1), 2) / (kCsfBlueYellow.a1 * std::sqrt(kPi / kCsfBlueYellow.b1));
  double w2 = std::pow(sum(by2), 2) / (kCsfBlueYellow.a2 * std::sqrt(kPi / kCsfBlueYellow.b2));
  k.blueYellowWeight[0] = w1 / (w1 + w2);
  k.blueYellowWeight[1] = w2 / (w1 + w2);
  k.blueYellow[0] = normalised(by1);
  k.blueYellow[1] = normalised(by2);

  // Feature detectors: a Gaussian whose peak-to-trough distance (2 sigma) is the width of a human
  // edge detector, 0.082 degrees; radius 3 sigma.
  const double sigma = 0.5 * 0.082 * ppd;
  const int fr = int(std::ceil(3.0 * sigma));
  k.featureRadius = fr;
  std::vector<double> g(size_t(2 * fr + 1)), d1(g.size()), d2(g.size());
  for (int i = -fr; i <= fr; ++i) {
    double x = double(i), gi = std::exp(-x * x / (2 * sigma * sigma));
    g[size_t(i + fr)] = gi;
    d1[size_t(i + fr)] = -x * gi;
    d2[size_t(i + fr)] = (x * x / (sigma * sigma) - 1) * gi;
  }
  // The 2D detector d(x) g(y) normalised by sign is the 1D derivative normalised by sign times g of sum 1.
  k.gauss = normalised(g);
  k.edge = signNormalised(d1);
  k.point = signNormalised(d2);

  std::array<double, 3> green = huntLab(linearRgbToXyz({0, 1, 0})), blue = huntLab(linearRgbToXyz({0, 0, 1}));
  k.cmax = std::pow(hyab(green, blue), kFlipQc);
  return k;
}

namespace {

struct Plane {
  int w = 0, h = 0;
  std::vector<double> v;
};

// Separable filter: kx along rows, then ky along columns; borders repeat the edge pixel. Taps are
// summed in kernel order for every pixel (the GPU pass sums in the same order).
Plane filter(const Plane& in, const std::vector<double>& kx, const std::vector<double>& ky) {
  const int rx = int(kx.size()) / 2, ry = int(ky.size()) / 2, w = in.w, h = in.h;
  Plane tmp{w, h, std::vector<double>(in.v.size())}, out = tmp;
  std::vector<double> row(size_t(w + 2 * rx));
  for (int y = 0; y < h; ++y) {
    const double* src = &in.v[size_t(y) * size_t(w)];
    for (int x = -rx; x < w + rx; ++x) row[size_t(x + rx)] = src[std::clamp(x, 0, w - 1)];
    double* dst = &tmp.v[size_t(y) * size_t(w)];
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (size_t i = 0; i < kx.size(); ++i) s += kx[i] * row[size_t(x) + i];
      dst[x] = s;
    }
  }
  for (int y = 0; y < h; ++y) {
    double* dst = &out.v[size_t(y) * size_t(w)];
    for (size_t i = 0; i < ky.size(); ++i) {
      const double k = ky[i];
      const double* src = &tmp.v[size_t(std::clamp(y + int(i) - ry, 0, h - 1)) * size_t(w)];
      for (int x = 0; x < w; ++x) dst[x] += k * src[x];
    }
  }
  return out;
}

// One image's share of the computation: its filtered colour as Hunt-adjusted L*a*b*, and the
// magnitudes of its edge and point responses.
struct Prepared {
  std::vector<std::array<double, 3>> lab;
  std::vector<double> edge, point;
};

Prepared prepare(const RgbaImage& img, const FlipKernels& k) {
  const int w = img.width, h = img.height;
  const size_t n = size_t(w) * size_t(h);
  static const std::array<double, 256> linear = [] {
    std::array<double, 256> t{};
    for (int b = 0; b < 256; ++b) t[size_t(b)] = srgbToLinear(b);
    return t;
  }();
  Plane y{w, h, std::vector<double>(n)}, cx = y, cz = y;
  for (size_t i = 0; i < n; ++i) {
    std::array<double, 3> o =
        xyzToYcxcz(linearRgbToXyz({linear[img.px[i * 4]], linear[img.px[i * 4 + 1]], linear[img.px[i * 4 + 2]]}));
    y.v[i] = o[0], cx.v[i] = o[1], cz.v[i] = o[2];
  }
  Plane fy = filter(y, k.achromatic, k.achromatic), fcx = filter(cx, k.redGreen, k.redGreen);
  Plane fz1 = filter(cz, k.blueYellow[0], k.blueYellow[0]), fz2 = filter(cz, k.blueYellow[1], k.blueYellow[1]);
  Prepared p;
  p.lab.resize(n);
  for (size_t i = 0; i < n; ++i) {
    double z = k.blueYellowWeight[0] * fz1.v[i] + k.blueYellowWeight[1] * fz2.v[i];
    std::array<double, 3> rgb = xyzToLinearRgb(ycxczToXyz({fy.v[i], fcx.v[i], z}));
    for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
    p.lab[i] = huntLab(linearRgbToXyz(rgb));
  }
  // Features on the unfiltered achromatic channel, normalised to [0, 1]: (Y + 16) / 116.
  Plane lum{w, h, std::vector<double>(n)};
  for (size_t i = 0; i < n; ++i) lum.v[i] = (y.v[i] + 16.0) / 116.0;
  Plane ex = filter(lum, k.edge, k.gauss), ey = filter(lum, k.gauss, k.edge);
  Plane px = filter(lum, k.point, k.gauss), py = filter(lum, k.gauss, k.point);
  p.edge.resize(n);
  p.point.resize(n);
  for (size_t i = 0; i < n; ++i) {
    p.edge[i] = std::hypot(ex.v[i], ey.v[i]);
    p.point[i] = std::hypot(px.v[i], py.v[i]);
  }
  return p;
}

}  // namespace

double flipPixel(const std::array<double, 3>& labRef, const std::array<double, 3>& labTest, double edgeRef,
                 double edgeTest, double pointRef, double pointTest, double cmax) {
  // Colour: HyAB ^ qc, differences below pc x cmax compressed onto [0, pt], the rest onto [pt, 1].
  const double c = std::pow(hyab(labRef, labTest), kFlipQc), knee = kFlipPc * cmax;
  const double colour = c < knee ? kFlipPt / knee * c : kFlipPt + (c - knee) / (cmax - knee) * (1.0 - kFlipPt);
  // Features: the larger difference of edge or point magnitude, over sqrt 2 (the largest magnitude), ^ qf.
  const double f = std::max(std::abs(edgeRef - edgeTest), std::abs(pointRef - pointTest));
  const double feature = std::pow(f / std::sqrt(2.0), kFlipQf);
  return std::pow(colour, 1.0 - feature);
}

std::vector<float> flipMap(const RgbaImage& reference, const RgbaImage& test, double ppd) {
  if (reference.width != test.width || reference.height != test.height || reference.px.size() != test.px.size() ||
      reference.px.size() != size_t(reference.width) * size_t(reference.height) * 4)
    throw std::invalid_argument("FLIP needs two RGBA images of the same size");
  const FlipKernels k = flipKernels(ppd);
  // The two images' filters are independent: one on another thread (the same values either way).
  std::future<Prepared> later = std::async(std::launch::async, [&] { return prepare(reference, k); });
  const Prepared t = prepare(test, k), r = later.get();
  std::vector<float> out(r.edge.size());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = float(flipPixel(r.lab[i], t.lab[i], r.edge[i], t.edge[i], r.point[i], t.point[i], k.cmax));
  return out;
}

FlipStats flipStats(const std::vector<float>& map) {
  if (map.empty()) return {};
  std::vector<double> v(map.begin(), map.end());
  double s = 0;
  for (double x : v) s += x;
  return {s / double(v.size()), percentile(std::move(v), 95)};
}

RgbaImage asSeen(const RgbaImage& frame) {
  RgbaImage out = frame;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x)
      if (isClear(frame, x, y))
        std::copy(kSkyRgba.begin(), kSkyRgba.end(), &out.px[(size_t(y) * size_t(frame.width) + size_t(x)) * 4]);
  return out;
}

RgbaImage flipImage(const std::vector<float>& map, int width, int height) {
  // Control points of a dark-to-bright ramp whose lightness rises steadily, so an error's size reads
  // from its brightness in grey too.
  static const std::array<std::array<double, 3>, 5> kRamp = {
      {{0, 0, 4}, {80, 18, 123}, {183, 55, 121}, {252, 137, 97}, {252, 253, 191}}};
  RgbaImage img{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
  for (size_t i = 0; i < map.size() && i * 4 < img.px.size(); ++i) {
    double t = std::clamp(double(map[i]), 0.0, 1.0) * double(kRamp.size() - 1);
    size_t a = std::min(size_t(t), kRamp.size() - 2);
    double f = t - double(a);
    for (int c = 0; c < 3; ++c)
      img.px[i * 4 + size_t(c)] = uint8_t(std::lround(kRamp[a][size_t(c)] * (1 - f) + kRamp[a + 1][size_t(c)] * f));
  }
  return img;
}

}  // namespace lb
