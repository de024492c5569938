#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "stats.h"

namespace lb {

static void checkSameSize(const RgbaImage& a, const RgbaImage& b) {
  if (a.width != b.width || a.height != b.height || a.px.size() != b.px.size() ||
      a.px.size() != size_t(a.width) * size_t(a.height) * 4)
    throw std::invalid_argument("image comparison needs two RGBA images of the same size");
}

ImageError compareImages(const RgbaImage& a, const RgbaImage& b, int threshold) {
  checkSameSize(a, b);
  ImageError e;
  size_t n = size_t(a.width) * size_t(a.height);
  double sq = 0, absSum = 0;
  long over = 0;
  std::vector<double> maxDiff(n);
  for (size_t i = 0; i < n; ++i) {
    int m = 0;
    for (int c = 0; c < 3; ++c) {
      int d = std::abs(int(a.px[i * 4 + c]) - int(b.px[i * 4 + c]));
      sq += double(d) * d;
      absSum += d;
      m = std::max(m, d);
    }
    maxDiff[i] = m;
    over += m > threshold;
    e.changedPixels += m > 0;
  }
  double mse = sq / double(n * 3);
  e.psnrDb = mse == 0 ? kPsnrIdentical : std::min(kPsnrIdentical, 10.0 * std::log10(255.0 * 255.0 / mse));
  e.meanAbsDiff = absSum / double(n * 3);
  e.fractionOver = double(over) / double(n);
  e.p99AbsDiff = percentile(maxDiff, 99);
  e.ssim = ssim(a, b);
  return e;
}

const SsimConstants& ssimConstants() {
  static const SsimConstants k = [] {
    SsimConstants c{{}, {0.299, 0.587, 0.114}, std::pow(0.01 * 255, 2), std::pow(0.03 * 255, 2)};
    const double sigma = 1.5;
    double sum = 0;
    for (int i = 0; i < 11; ++i) sum += c.window[i] = std::exp(-double((i - 5) * (i - 5)) / (2 * sigma * sigma));
    for (double& v : c.window) v /= sum;
    return c;
  }();
  return k;
}

static std::vector<double> luma(const RgbaImage& img) {
  const double* w = ssimConstants().luma;
  std::vector<double> y(size_t(img.width) * size_t(img.height));
  for (size_t i = 0; i < y.size(); ++i)
    y[i] = w[0] * img.px[i * 4] + w[1] * img.px[i * 4 + 1] + w[2] * img.px[i * 4 + 2];
  return y;
}

// Separable Gaussian filter over "valid" window positions only (no padding), as in the reference code.
static std::vector<double> filterValid(const std::vector<double>& in, int w, int h, const std::vector<double>& k) {
  int r = int(k.size()) / 2, ow = w - 2 * r, oh = h - 2 * r;
  std::vector<double> tmp(size_t(ow) * size_t(h)), out(size_t(ow) * size_t(oh));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int i = 0; i < int(k.size()); ++i) s += k[size_t(i)] * in[size_t(y) * size_t(w) + size_t(x + i)];
      tmp[size_t(y) * size_t(ow) + size_t(x)] = s;
    }
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int i = 0; i < int(k.size()); ++i) s += k[size_t(i)] * tmp[size_t(y + i) * size_t(ow) + size_t(x)];
      out[size_t(y) * size_t(ow) + size_t(x)] = s;
    }
  return out;
}

double ssim(const RgbaImage& a, const RgbaImage& b) {
  checkSameSize(a, b);
  const int kSize = 11;
  const SsimConstants& constants = ssimConstants();
  const double c1 = constants.c1, c2 = constants.c2;
  if (a.width < kSize || a.height < kSize) throw std::invalid_argument("SSIM needs images of at least 11x11");
  const std::vector<double> k(constants.window, constants.window + kSize);
  auto x = luma(a), y = luma(b);
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    xx[i] = x[i] * x[i];
    yy[i] = y[i] * y[i];
    xy[i] = x[i] * y[i];
  }
  int w = a.width, h = a.height;
  auto mx = filterValid(x, w, h, k), my = filterValid(y, w, h, k);
  auto sxx = filterValid(xx, w, h, k), syy = filterValid(yy, w, h, k), sxy = filterValid(xy, w, h, k);
  double total = 0;
  for (size_t i = 0; i < mx.size(); ++i) {
    double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
    total += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return total / double(mx.size());
}

bool isClear(const RgbaImage& img, int x, int y) {
  const uint8_t* p = &img.px[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return p[0] == 255 && p[1] == 0 && p[2] == 255;
}

long crackPixels(const RgbaImage& img, const RgbaImage& reference, std::vector<uint8_t>* mask, int reach) {
  checkSameSize(img, reference);
  int w = img.width, h = img.height;
  if (mask) mask->assign(size_t(w) * size_t(h), 0);
  auto terrainAt = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && !isClear(img, x, y); };
  auto enclosed = [&](int x, int y, int dx, int dy) {
    bool before = false, after = false;
    for (int s = 1; s <= reach; ++s) {
      before = before || terrainAt(x - dx * s, y - dy * s);
      after = after || terrainAt(x + dx * s, y + dy * s);
    }
    return before && after;
  };
  // A candidate is a crack unless its clear region of img (8-connected) reaches the background: a
  // pixel clear in both images, or on the image border, past which the background may continue
  // off-screen (a silhouette gap, not a hole). Only the regions holding candidates are searched, and
  // a search stops at the first background pixel, so the sky's region is never walked whole.
  enum : uint8_t { kUnknown = 0, kBackground = 1, kHole = 2, kQueued = 3 };
  std::vector<uint8_t> region(size_t(w) * size_t(h), kUnknown);
  std::vector<int> queue;
  auto resolve = [&](int start) {
    queue.assign(1, start);
    region[size_t(start)] = kQueued;
    bool background = false;
    for (size_t q = 0; q < queue.size() && !background; ++q) {
      int p = queue[q], px = p % w, py = p / w;
      if (isClear(reference, px, py) || px == 0 || py == 0 || px == w - 1 || py == h - 1) background = true;
      for (int dy = -1; dy <= 1 && !background; ++dy)
        for (int dx = -1; dx <= 1 && !background; ++dx) {
          int x = px + dx, y = py + dy;
          if (x < 0 || y < 0 || x >= w || y >= h || !isClear(img, x, y)) continue;
          uint8_t& r = region[size_t(y) * size_t(w) + size_t(x)];
          if (r == kBackground) background = true;
          if (r != kUnknown) continue;
          r = kQueued;
          queue.push_back(y * w + x);
        }
    }
    for (int p : queue) region[size_t(p)] = background ? kBackground : kHole;
  };
  long count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!isClear(img, x, y) || isClear(reference, x, y)) continue;
      if (!enclosed(x, y, 1, 0) && !enclosed(x, y, 0, 1)) continue;
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      if (region[i] == kUnknown) resolve(y * w + x);
      if (region[i] != kHole) continue;
      ++count;
      if (mask) (*mask)[i] = 1;
    }
  return count;
}

}  // namespace lb
