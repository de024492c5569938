// Image metrics on synthetic images with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/image_metrics.h"

using namespace lb;

static RgbaImage solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4)};
  for (size_t i = 0; i < img.px.size(); i += 4) {
    img.px[i] = r;
    img.px[i + 1] = g;
    img.px[i + 2] = b;
    img.px[i + 3] = 255;
  }
  return img;
}

static void setPx(RgbaImage& img, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  uint8_t* p = &img.px[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  p[0] = r;
  p[1] = g;
  p[2] = b;
}

TEST(ImageMetrics, IdenticalImages) {
  RgbaImage a = solid(32, 24, 10, 120, 30);
  for (int i = 0; i < 32; ++i) setPx(a, i, i % 24, uint8_t(i * 7), 3, 200);
  ImageError e = compareImages(a, a);
  EXPECT_EQ(e.psnrDb, kPsnrIdentical);
  EXPECT_DOUBLE_EQ(e.ssim, 1.0);
  EXPECT_EQ(e.meanAbsDiff, 0.0);
  EXPECT_EQ(e.changedPixels, 0);
}

TEST(ImageMetrics, PsnrOfUniformOffsetIsExact) {
  RgbaImage a = solid(16, 16, 100, 100, 100), b = solid(16, 16, 110, 110, 110);
  ImageError e = compareImages(a, b, 16);
  EXPECT_NEAR(e.psnrDb, 20.0 * std::log10(255.0 / 10.0), 1e-12);
  EXPECT_DOUBLE_EQ(e.meanAbsDiff, 10.0);
  EXPECT_EQ(e.fractionOver, 0.0);  // 10 <= 16
  EXPECT_EQ(e.changedPixels, 256);
  // A constant brightness shift leaves structure and contrast intact: SSIM only loses luminance.
  double mu = 100, nu = 110, c1 = std::pow(0.01 * 255, 2);
  EXPECT_NEAR(e.ssim, (2 * mu * nu + c1) / (mu * mu + nu * nu + c1), 1e-9);
}

TEST(ImageMetrics, FractionOverThresholdCountsPixels) {
  RgbaImage a = solid(20, 20, 0, 0, 0), b = a;
  for (int x = 0; x < 20; ++x) setPx(b, x, 3, 0, 40, 0);  // 20 of 400 pixels differ by 40
  ImageError e = compareImages(a, b, 16);
  EXPECT_DOUBLE_EQ(e.fractionOver, 20.0 / 400.0);
  EXPECT_EQ(e.changedPixels, 20);
  EXPECT_LT(e.ssim, 1.0);
}

TEST(ImageMetrics, CrackPixelsFindHolesNotSilhouettes) {
  const int w = 40, h = 30;
  RgbaImage ref = solid(w, h, 60, 90, 40);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < w; ++x) setPx(ref, x, y, 255, 0, 255);  // sky above the horizon
  RgbaImage img = ref;
  // A coarser LOD's horizon sits lower: an 8-pixel-wide, 3-deep dip is a silhouette difference.
  for (int y = 8; y < 11; ++y)
    for (int x = 10; x < 18; ++x) setPx(img, x, y, 255, 0, 255);
  // A 3-wide, 2-deep notch is enclosed within 3 pixels but opens onto the sky: still a silhouette.
  for (int y = 8; y < 10; ++y)
    for (int x = 30; x < 33; ++x) setPx(img, x, y, 255, 0, 255);
  for (int x = 5; x < 25; ++x) setPx(img, x, 20, 255, 0, 255);  // a 20-pixel crack inside the terrain
  std::vector<uint8_t> mask;
  EXPECT_EQ(crackPixels(img, ref, &mask), 20);
  EXPECT_EQ(mask[size_t(20 * w + 5)], 1);
  EXPECT_EQ(mask[size_t(9 * w + 12)], 0);
  EXPECT_EQ(mask[size_t(9 * w + 31)], 0);
  // A gap on the image border may open onto background beyond the image: not counted either.
  RgbaImage edge = img;
  for (int y = 14; y < 16; ++y) setPx(edge, 0, y, 255, 0, 255);
  EXPECT_EQ(crackPixels(edge, ref), 20);
  // The same crack reaching up to the sky (a column of clear pixels at x = 4 touching its first
  // pixel diagonally) joins the background and is not counted: the price of never flagging a silhouette.
  for (int y = 8; y < 20; ++y) setPx(img, 4, y, 255, 0, 255);
  EXPECT_EQ(crackPixels(img, ref), 0);
  EXPECT_EQ(crackPixels(ref, ref), 0);
}
