// The image layer's chart shapes (draw_line, fill_circle, fill_rect): coverage where the geometry
// says, nothing beyond, clipping at the edges, and the same pixels on every run.
#include <gtest/gtest.h>

#include "image/image.h"

namespace {

using glint::Image8;
using glint::Rgb8;

constexpr Rgb8 kWhite{255, 255, 255}, kBlack{0, 0, 0};

TEST(Draw, HorizontalLineCoversItsRowOnly) {
  Image8 img(20, 10, kWhite);
  // A 1-pixel line through the centres of row 4.
  glint::draw_line(img, 2, 4.5, 17, 4.5, kBlack, 1.0);
  for (int x = 3; x <= 16; ++x) EXPECT_EQ(img.at(x, 4), kBlack) << x;
  for (int x = 0; x < 20; ++x) {
    EXPECT_EQ(img.at(x, 2), kWhite) << x;
    EXPECT_EQ(img.at(x, 6), kWhite) << x;
  }
  EXPECT_EQ(img.at(19, 4), kWhite);  // beyond the cap
}

TEST(Draw, CircleAndRectCoverage) {
  Image8 img(21, 21, kWhite);
  glint::fill_circle(img, 10.5, 10.5, 5, kBlack);
  EXPECT_EQ(img.at(10, 10), kBlack);
  EXPECT_EQ(img.at(13, 10), kBlack);  // 3 from the centre
  EXPECT_EQ(img.at(17, 10), kWhite);  // 6.5 from the centre
  EXPECT_EQ(img.at(0, 0), kWhite);
  const Rgb8 edge = img.at(15, 10);  // 4.5 + 0.5 from the centre: half covered
  EXPECT_GT(edge[0], 64);
  EXPECT_LT(edge[0], 192);
  Image8 r(10, 10, kWhite);
  glint::fill_rect(r, 2, 2, 5.5, 4, kBlack);
  EXPECT_EQ(r.at(2, 2), kBlack);
  EXPECT_EQ(r.at(4, 3), kBlack);
  EXPECT_NEAR(r.at(5, 3)[0], 127.5, 1);  // half of the pixel [5, 6) covered
  EXPECT_EQ(r.at(2, 4), kWhite);
}

TEST(Draw, ClipsAtTheEdgesAndIsDeterministic) {
  Image8 a(16, 16, kWhite), b(16, 16, kWhite);
  for (Image8* img : {&a, &b}) {
    glint::draw_line(*img, -10, -3, 40, 25, {200, 30, 30}, 2.5);
    glint::fill_circle(*img, 15, 0, 6, {30, 30, 200});
    glint::fill_rect(*img, -5, 12, 30, 40, {30, 200, 30});
  }
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.at(8, 8), kWhite);
}

}  // namespace
