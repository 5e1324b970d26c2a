// The image layer: sRGB encoding, PNG bytes and files, the heat colour map, text, the heat map with
// its scale and the contact sheet. GLINT_IMAGE_DEMO=DIR also writes demo images to DIR to look at.
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "image/image.h"
#include "io/atomic_file.h"
#include "test_support.h"

namespace glint {
namespace {

using glint::test::TempDir;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The inverse of the sRGB encoding (IEC 61966-2-1), to find where each 8-bit code begins.
double srgb_decode(double s) {
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

double luminance(Rgb8 c) {
  // Rec.709 relative luminance of an sRGB colour.
  return 0.2126 * srgb_decode(c[0] / 255.0) + 0.7152 * srgb_decode(c[1] / 255.0) +
         0.0722 * srgb_decode(c[2] / 255.0);
}

// A gradient test image with every channel varying.
Image8 gradient(int w, int h) {
  Image8 image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.set(x, y,
                {static_cast<std::uint8_t>(x * 255 / std::max(w - 1, 1)),
                 static_cast<std::uint8_t>(y * 255 / std::max(h - 1, 1)),
                 static_cast<std::uint8_t>((x * 7 + y * 13) % 256)});
    }
  }
  return image;
}

int count_differences(const Image8& a, const Image8& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) n += a.at(x, y) != b.at(x, y);
  }
  return n;
}

// ---- Image8 ----

TEST(Image8, SizeFillAndAccess) {
  Image8 image(3, 2, {1, 2, 3});
  EXPECT_EQ(image.pixels.size(), 18u);
  EXPECT_EQ(image.at(2, 1), (Rgb8{1, 2, 3}));
  image.set(2, 1, {9, 8, 7});
  EXPECT_EQ(image.at(2, 1), (Rgb8{9, 8, 7}));
  EXPECT_EQ(image.pixels[15], 9);  // row-major RGB: (2, 1) starts at 3 * (1 * 3 + 2)
  EXPECT_THROW(image.at(3, 0), std::out_of_range);
  EXPECT_THROW(image.set(0, -1, {}), std::out_of_range);
  EXPECT_THROW(Image8(-1, 2), std::invalid_argument);
}

// ---- srgb8 ----

TEST(Srgb8, KnownValues) {
  EXPECT_EQ(srgb8(0.0), 0);
  EXPECT_EQ(srgb8(1.0), 255);
  EXPECT_EQ(srgb8(0.5), 188);    // 255 (1.055 0.5^(1/2.4) - 0.055) = 187.516
  EXPECT_EQ(srgb8(0.214), 127);  // 127.489: 0.214 is just below the start of 128
  EXPECT_EQ(srgb8(0.18), 118);   // 18% grey: 117.9
  EXPECT_EQ(srgb8(0.001), 3);    // the linear segment: 255 * 12.92 * 0.001 = 3.29
  // Either side of the segments' meeting point: 255 * 0.0404500 = 10.31 from both formulas.
  EXPECT_EQ(srgb8(0.0031308), 10);
  EXPECT_EQ(srgb8(std::nextafter(0.0031308, 1.0)), 10);
  EXPECT_EQ(srgb8(std::nextafter(0.0031308, 0.0)), 10);
}

TEST(Srgb8, ClampsAndMapsNaNToBlack) {
  EXPECT_EQ(srgb8(-0.5), 0);
  EXPECT_EQ(srgb8(-kInf), 0);
  EXPECT_EQ(srgb8(kNaN), 0);
  EXPECT_EQ(srgb8(1.5), 255);
  EXPECT_EQ(srgb8(kInf), 255);
  EXPECT_EQ(srgb8(std::numeric_limits<double>::denorm_min()), 0);
}

TEST(Srgb8, EveryCodeStartsWhereTheFormulaSays) {
  // Code c covers encoded values [(c - 0.5)/255, (c + 0.5)/255): just below the linear value whose
  // encoding is (c + 0.5)/255 gives c, just above gives c + 1. A table would miss some of these.
  for (int c = 0; c < 255; ++c) {
    const double edge = srgb_decode((c + 0.5) / 255.0);
    EXPECT_EQ(srgb8(edge * (1 - 1e-9)), c) << "below the start of " << c + 1;
    EXPECT_EQ(srgb8(edge * (1 + 1e-9)), c + 1) << "above the start of " << c + 1;
  }
}

TEST(Srgb8, MonotoneOverAFineSweep) {
  int previous = 0;
  for (int i = 0; i <= 1'000'000; ++i) {
    const int code = srgb8(i / 1e6);
    ASSERT_GE(code, previous) << "at " << i / 1e6;
    ASSERT_LE(code - previous, 13) << "at " << i / 1e6;  // no gaps but at the steep dark end
    previous = code;
  }
  EXPECT_EQ(previous, 255);
}

// ---- PNG ----

struct Decoded {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;
};

Decoded decode(const std::vector<std::uint8_t>& png) {
  Decoded d;
  int channels = 0;
  stbi_uc* data = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &d.width,
                                        &d.height, &channels, 3);
  EXPECT_NE(data, nullptr) << stbi_failure_reason();
  EXPECT_EQ(channels, 3);
  if (data) {
    d.pixels.assign(data, data + 3 * d.width * d.height);
    stbi_image_free(data);
  }
  return d;
}

std::vector<std::string> chunk_types(const std::vector<std::uint8_t>& png) {
  std::vector<std::string> types;
  std::size_t at = 8;
  while (at + 8 <= png.size()) {
    const std::size_t length = (std::size_t{png[at]} << 24) | (std::size_t{png[at + 1]} << 16) |
                               (std::size_t{png[at + 2]} << 8) | png[at + 3];
    types.emplace_back(reinterpret_cast<const char*>(&png[at + 4]), 4);
    at += 12 + length;
  }
  EXPECT_EQ(at, png.size());
  return types;
}

TEST(Png, DecodesToTheSamePixels) {
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{256, 160}, std::pair{3, 77}}) {
    const Image8 image = gradient(w, h);
    const std::vector<std::uint8_t> png = encode_png(image);
    const std::vector<std::uint8_t> signature{137, 80, 78, 71, 13, 10, 26, 10};
    ASSERT_GE(png.size(), 8u);
    EXPECT_TRUE(std::equal(signature.begin(), signature.end(), png.begin()));
    const Decoded d = decode(png);
    EXPECT_EQ(d.width, w);
    EXPECT_EQ(d.height, h);
    EXPECT_EQ(d.pixels, image.pixels) << w << "x" << h;
  }
}

TEST(Png, SameBytesEveryTimeAndOnlyTheEssentialChunks) {
  const Image8 image = gradient(200, 120);
  const std::vector<std::uint8_t> first = encode_png(image);
  EXPECT_EQ(encode_png(image), first);
  // No time, text or gamma chunks that could make equal pixels differ.
  EXPECT_EQ(chunk_types(first), (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
}

// Rows fed as a render makes them (tiles of any height) give the whole image's bytes, and
// encoders running at once on other threads do not disturb each other.
TEST(Png, RowWriterGivesTheSameBytesInAnyChunksAndOnAnyThread) {
  const Image8 image = gradient(203, 121);
  const std::vector<std::uint8_t> whole = encode_png(image);
  const auto streamed = [&](int chunk) {
    std::vector<std::uint8_t> out;
    PngRowWriter writer(image.width, image.height, [&](const std::uint8_t* d, std::size_t n) {
      out.insert(out.end(), d, d + n);
    });
    for (int y = 0; y < image.height; y += chunk) {
      EXPECT_FALSE(writer.done());
      writer.add_rows(image.pixels.data() + 3 * static_cast<std::size_t>(y) * image.width,
                      std::min(chunk, image.height - y));
    }
    EXPECT_TRUE(writer.done());
    return out;
  };
  EXPECT_EQ(streamed(1), whole);
  EXPECT_EQ(streamed(16), whole);
  EXPECT_EQ(decode(streamed(7)).pixels, image.pixels);
  std::vector<std::vector<std::uint8_t>> results(4);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < results.size(); ++t)
    threads.emplace_back([&, t] { results[t] = streamed(static_cast<int>(t) + 1); });
  for (std::thread& t : threads) t.join();
  for (const auto& r : results) EXPECT_EQ(r, whole);
}

TEST(Png, RowWriterRefusesExtraRowsAndPassesOnTheSinksError) {
  const Image8 image = gradient(8, 4);
  PngRowWriter writer(8, 4, [](const std::uint8_t*, std::size_t) {});
  writer.add_rows(image.pixels.data(), 4);
  EXPECT_THROW(writer.add_rows(image.pixels.data(), 1), std::logic_error);
  EXPECT_THROW(PngRowWriter(0, 4, [](const std::uint8_t*, std::size_t) {}), std::invalid_argument);
  try {
    PngRowWriter failing(
        8, 4, [](const std::uint8_t*, std::size_t) { throw std::runtime_error("disk full"); });
    failing.add_rows(image.pixels.data(), 4);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full");
  }
}

TEST(Png, RejectsImagesWithoutPixels) {
  EXPECT_THROW(encode_png(Image8()), std::invalid_argument);
  EXPECT_THROW(encode_png(Image8(0, 5)), std::invalid_argument);
}

TEST(Png, WritesTheFile) {
  const TempDir dir;
  const Image8 image = gradient(40, 30);
  write_png(dir.file("a.png"), image);
  const std::string bytes = test::read_file(dir.file("a.png"));
  const std::vector<std::uint8_t> expected = encode_png(image);
  EXPECT_EQ(bytes, std::string(expected.begin(), expected.end()));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.png"});  // no temporary left
}

TEST(Png, MissingFolderThrowsOutputErrorNamingThePathAndLeavesNothing) {
  const TempDir dir;
  const std::string path = dir.file("no/such/folder/x.png");
  try {
    write_png(path, gradient(4, 4));
    FAIL() << "no exception";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Png, ReplacesAnExistingFileAtomically) {
  const TempDir dir;
  const std::string path = dir.file("out.png");
  const Image8 old_image = gradient(30, 20), new_image = gradient(50, 10);
  write_png(path, old_image);
  struct stat before {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  // A reader that opened the old file keeps reading the old file, whole: the new one is renamed
  // over it, never written into it.
  std::ifstream reader(path, std::ios::binary);
  write_png(path, new_image);
  std::ostringstream old_bytes;
  old_bytes << reader.rdbuf();
  const std::vector<std::uint8_t> old_png = encode_png(old_image), new_png = encode_png(new_image);
  EXPECT_EQ(old_bytes.str(), std::string(old_png.begin(), old_png.end()));
  EXPECT_EQ(test::read_file(path), std::string(new_png.begin(), new_png.end()));
  struct stat after {};
  ASSERT_EQ(::stat(path.c_str(), &after), 0);
  EXPECT_NE(before.st_ino, after.st_ino);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.png"});
}

// ---- heat_colour ----

TEST(HeatColour, EndsAndClamping) {
  const Rgb8 zero = heat_colour(0), one = heat_colour(1);
  EXPECT_LE(zero[0] + zero[1] + zero[2], 10);  // near-black
  EXPECT_GT(luminance(one), 0.85);             // pale yellow
  EXPECT_EQ(heat_colour(-3), zero);
  EXPECT_EQ(heat_colour(7), one);
  EXPECT_EQ(heat_colour(kInf), one);
  EXPECT_EQ(heat_colour(-kInf), zero);
  EXPECT_EQ(heat_colour(kNaN), kHeatNan);
  // Published inferno entries that are knots of the table: 0, 0.5 (entry 127.5: between), 1.
  EXPECT_EQ(zero, (Rgb8{0, 0, 4}));
  EXPECT_EQ(one, (Rgb8{252, 255, 164}));
}

TEST(HeatColour, LuminanceRises) {
  // Strictly at every 8-bit step of the input, and never down by more than the rounding of one
  // channel on a fine sweep (each channel is rounded on its own).
  double previous = -1;
  for (int i = 0; i <= 255; ++i) {
    const double l = luminance(heat_colour(i / 255.0));
    EXPECT_GT(l, previous) << "at " << i << "/255";
    previous = l;
  }
  previous = -1;
  for (int i = 0; i <= 100'000; ++i) {
    const double l = luminance(heat_colour(i / 1e5));
    EXPECT_GT(l, previous - 0.003) << "at " << i / 1e5;
    previous = std::max(previous, l);
  }
}

TEST(HeatColour, NaNColourIsNotOnTheMap) {
  int nearest = 3 * 255;
  for (int i = 0; i <= 1000; ++i) {
    const Rgb8 c = heat_colour(i / 1000.0);
    nearest = std::min(nearest, std::abs(c[0] - kHeatNan[0]) + std::abs(c[1] - kHeatNan[1]) +
                                    std::abs(c[2] - kHeatNan[2]));
  }
  EXPECT_GT(nearest, 200);
}

// ---- text ----

TEST(Text, DrawsPixelsInsideItsBox) {
  const Image8 blank(120, 30, {10, 10, 10});
  Image8 image = blank;
  const int width = draw_text(image, 5, 4, "Hello 0.5 LSB", {250, 250, 250}, 14);
  EXPECT_EQ(width, text_width("Hello 0.5 LSB", 14));
  EXPECT_GT(count_differences(image, blank), 40);
  bool brightest = false;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y) == blank.at(x, y)) continue;
      EXPECT_GE(x, 5 - 1);  // glyphs may start a pixel left of the pen (bearing, subpixel)
      EXPECT_LT(x, 5 + width + 1);
      EXPECT_GE(y, 4);
      EXPECT_LT(y, 4 + 14);
      const Rgb8 c = image.at(x, y);
      EXPECT_TRUE(c[0] == c[1] && c[1] == c[2]) << "grey over grey stays grey";
      brightest = brightest || c[0] == 250;
    }
  }
  EXPECT_TRUE(brightest) << "full coverage blends to the text colour itself";
}

TEST(Text, WidthGrowsWithTextAndHeight) {
  EXPECT_EQ(text_width(""), 0);
  EXPECT_LT(text_width("1"), text_width("10"));
  EXPECT_LT(text_width("10"), text_width("10 LSB"));
  EXPECT_LT(text_width("10 LSB", 12), text_width("10 LSB", 24));
  EXPECT_GT(text_width("W"), text_width("i"));  // proportional, not fixed-width
  EXPECT_THROW(text_width("x", 0), std::invalid_argument);
}

TEST(Text, Deterministic) {
  Image8 a(100, 20), b(100, 20);
  draw_text(a, 2, 2, "tau 0.871", {200, 120, 40});
  draw_text(b, 2, 2, "tau 0.871", {200, 120, 40});
  EXPECT_EQ(a.pixels, b.pixels);
}

TEST(Text, OtherBytesAreDrawnAsQuestionMarks) {
  for (const std::string odd : {"\x01", "\x7f", "\xff", "\xc3"}) {
    Image8 a(20, 20), b(20, 20);
    draw_text(a, 2, 2, odd, {255, 255, 255});
    draw_text(b, 2, 2, "?", {255, 255, 255});
    EXPECT_EQ(a.pixels, b.pixels) << static_cast<int>(static_cast<unsigned char>(odd[0]));
  }
  EXPECT_EQ(text_width("a\tb"), text_width("a?b"));
  EXPECT_EQ(text_width("\xff\xfe"), text_width("??"));
  // Valid UTF-8 is drawn with the font's own glyph: "±" is not a question mark.
  Image8 a(20, 20), b(20, 20);
  draw_text(a, 2, 2, "\xc2\xb1", {255, 255, 255});
  draw_text(b, 2, 2, "?", {255, 255, 255});
  EXPECT_NE(a.pixels, b.pixels);
}

TEST(Text, ClippedToTheImage) {
  const Image8 blank(30, 10);
  Image8 image = blank;
  // Partly outside on every side: draws what falls inside, touches nothing else.
  draw_text(image, -7, -6, "Clipped text", {255, 255, 255}, 20);
  EXPECT_GT(count_differences(image, blank), 0);
  Image8 outside = blank;
  draw_text(outside, 40, 0, "x", {255, 255, 255});
  draw_text(outside, 0, -30, "x", {255, 255, 255});
  draw_text(outside, -500, 0, "x", {255, 255, 255});
  EXPECT_EQ(outside.pixels, blank.pixels);
}

TEST(Text, FitTextEndsInAnEllipsis) {
  const std::string label = "schlick n=50 eps=1e-3 a long label";
  EXPECT_EQ(fit_text(label, 1000), label);
  const std::string cut = fit_text(label, 80);
  EXPECT_LE(text_width(cut), 80);
  EXPECT_GT(text_width(cut), 40);
  EXPECT_EQ(cut.substr(cut.size() - 3), "\xe2\x80\xa6");
  EXPECT_EQ(label.rfind(cut.substr(0, cut.size() - 3), 0), 0u);  // a prefix of the label
  EXPECT_EQ(fit_text(label, 2), "");
}

TEST(Text, SameFromManyThreads) {
  // The font loads on first use from whichever thread comes first; in ctest's one process per
  // test this is that first use.
  std::vector<Image8> images(4, Image8(120, 20));
  std::vector<std::vector<std::uint8_t>> pngs(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < images.size(); ++i) {
    threads.emplace_back([&, i] {
      draw_text(images[i], 1, 1, "threads 0.25 LSB", {255, 255, 255});
      pngs[i] = encode_png(images[i]);
    });
  }
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 1; i < images.size(); ++i) {
    EXPECT_EQ(images[i].pixels, images[0].pixels);
    EXPECT_EQ(pngs[i], pngs[0]);
  }
}

// A missing font is named with the Debian package that ships the default. The font is loaded once
// per process, so this runs in a fresh one (gtest re-executes the test binary).
TEST(TextDeathTest, MissingFontNamesFileAndPackage) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        ::setenv("GLINT_FONT", "/nonexistent/glint-font.ttf", 1);
        try {
          text_width("x");
        } catch (const std::runtime_error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::_Exit(3);
        }
        std::_Exit(0);
      },
      ::testing::ExitedWithCode(3), "/nonexistent/glint-font.ttf.*fonts-dejavu-core");
}

// ---- heatmap_with_scale ----

TEST(Heatmap, MapPixelsAreTheColourMap) {
  const int w = 40, h = 30;
  std::vector<double> error(w * h, 0.0);
  error[0] = 0.75;      // (0, 0)
  error[1] = -0.75;     // (1, 0): by magnitude
  error[2] = 5.0;       // (2, 0): above the scale, clamped
  error[w] = kNaN;      // (0, 1)
  error[w + 1] = kInf;  // (1, 1)
  const Image8 image = heatmap_with_scale(error, w, h, 2.0, "error");
  EXPECT_EQ(image.at(0, 0), heat_colour(0.75 / 2.0));
  EXPECT_EQ(image.at(1, 0), heat_colour(0.75 / 2.0));
  EXPECT_EQ(image.at(2, 0), heat_colour(1.0));
  EXPECT_EQ(image.at(0, 1), kHeatNan);
  EXPECT_EQ(image.at(1, 1), heat_colour(1.0));
  EXPECT_EQ(image.at(w - 1, h - 1), heat_colour(0.0));  // no error: the map's 0 colour
  EXPECT_GT(image.width, w + 40);                       // the bar and its labels to the right
  EXPECT_GE(image.height, h);
}

// The colour bar: a column in the margin that runs from heat_colour(1) down to heat_colour(0).
void expect_colour_bar(const Image8& image, int map_width) {
  for (int x = map_width; x < image.width; ++x) {
    int top = -1, bottom = -1;
    for (int y = 0; y < image.height; ++y) {
      if (top < 0 && image.at(x, y) == heat_colour(1.0)) top = y;
      if (image.at(x, y) == heat_colour(0.0)) bottom = y;
    }
    if (top < 0 || bottom < 0) continue;
    EXPECT_GE(bottom - top, 60) << "bar at least 64 pixels tall";
    for (int y = top + 1; y <= bottom; ++y) {
      EXPECT_LE(luminance(image.at(x, y)), luminance(image.at(x, y - 1)) + 1e-12) << y;
    }
    return;
  }
  ADD_FAILURE() << "no colour bar found right of the map";
}

TEST(Heatmap, HasAColourBarAndLabels) {
  const int w = 256, h = 160;
  std::vector<double> error(w * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) error[y * w + x] = 2.0 * x / (w - 1);
  }
  const Image8 image = heatmap_with_scale(error, w, h, 2.0, "gradient 0..2 LSB");
  EXPECT_EQ(image.height, h);  // a map this tall holds the bar
  expect_colour_bar(image, w);
  // Text: light pixels in the margin that are not on the colour map.
  int light = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = w; x < image.width; ++x) {
      const Rgb8 c = image.at(x, y);
      light += c[0] > 150 && c[0] == c[1] && c[1] == c[2];
    }
  }
  EXPECT_GT(light, 50);
  EXPECT_EQ(heatmap_with_scale(error, w, h, 2.0, "gradient 0..2 LSB").pixels, image.pixels);
}

TEST(Heatmap, SmallMapGrowsTheImageToFitTheScale) {
  const int w = 64, h = 48;
  const std::vector<double> error(w * h, 0.25);
  const Image8 image = heatmap_with_scale(error, w, h, 1.0, "small");
  EXPECT_GT(image.height, h);
  EXPECT_EQ(image.at(w - 1, h - 1), heat_colour(0.25));
  expect_colour_bar(image, w);
}

TEST(Heatmap, NaNKeyOnlyWhenNeeded) {
  std::vector<double> error(20 * 20, 0.5);
  const auto has_nan_colour = [](const Image8& image, int from_x) {
    for (int y = 0; y < image.height; ++y) {
      for (int x = from_x; x < image.width; ++x) {
        if (image.at(x, y) == kHeatNan) return true;
      }
    }
    return false;
  };
  EXPECT_FALSE(has_nan_colour(heatmap_with_scale(error, 20, 20, 1.0, "t"), 20));
  error[7] = kNaN;
  EXPECT_TRUE(has_nan_colour(heatmap_with_scale(error, 20, 20, 1.0, "t"), 20));
}

TEST(Heatmap, RejectsBadArguments) {
  const std::vector<double> error(12, 0.0);
  EXPECT_THROW(heatmap_with_scale(error, 4, 4, 1.0, ""), std::invalid_argument);
  EXPECT_THROW(heatmap_with_scale(error, 4, 3, 0.0, ""), std::invalid_argument);
  EXPECT_THROW(heatmap_with_scale(error, 4, 3, kNaN, ""), std::invalid_argument);
  EXPECT_THROW(heatmap_with_scale(error, 4, 3, kInf, ""), std::invalid_argument);
  EXPECT_THROW(heatmap_with_scale({}, 0, 0, 1.0, ""), std::invalid_argument);
  EXPECT_NO_THROW(heatmap_with_scale(error, 4, 3, 1.0, ""));
}

TEST(Heatmap, ScalesOfEveryMagnitudeLayOut) {
  // The tick choice must find 3 to 5 labels for any scale: no throw, a bar every time.
  for (const double scale : {1e-7, 0.003, 0.1, 0.37, 1.0, 1.7, 2.0, 3.0, 8.0, 10.0, 99.0, 1e6}) {
    const std::vector<double> error(30 * 20, scale / 2);
    const Image8 image = heatmap_with_scale(error, 30, 20, scale, "scale");
    EXPECT_EQ(image.at(0, 0), heat_colour(0.5)) << scale;
    expect_colour_bar(image, 30);
  }
}

// ---- contact_sheet ----

TEST(ContactSheet, FiveTilesInThreeColumns) {
  std::vector<Image8> images;
  for (int i = 0; i < 5; ++i) images.emplace_back(40, 30, Rgb8{200, static_cast<uint8_t>(i), 0});
  std::vector<std::pair<std::string, const Image8*>> tiles;
  for (int i = 0; i < 5; ++i) tiles.push_back({"tile " + std::to_string(i), &images[i]});
  const Image8 sheet = contact_sheet(tiles, 3);
  // 3 cells of 40 and 4 gaps of 8 across; 2 rows of (14 label + 4 + 30) and 3 gaps of 8 down.
  EXPECT_EQ(sheet.width, 3 * 40 + 4 * 8);
  EXPECT_EQ(sheet.height, 2 * (14 + 4 + 30) + 3 * 8);
  // Tile i's top-left pixel sits under its label.
  for (int i = 0; i < 5; ++i) {
    const int x = 8 + (i % 3) * 48, y = 8 + (i / 3) * (48 + 8) + 18;
    EXPECT_EQ(sheet.at(x, y), images[i].at(0, 0)) << i;
    EXPECT_EQ(sheet.at(x + 39, y + 29), images[i].at(0, 0)) << i;
  }
  // The sixth cell is empty background, as are the corners.
  EXPECT_EQ(sheet.at(sheet.width - 9, sheet.height - 9), sheet.at(0, 0));
  EXPECT_EQ(contact_sheet(tiles, 3).pixels, sheet.pixels);
  // More columns than tiles: one row.
  EXPECT_EQ(contact_sheet(tiles, 9).width, 5 * 40 + 6 * 8);
}

TEST(ContactSheet, DifferentSizesLongLabels) {
  const Image8 big(60, 40, {255, 0, 0}), small(20, 10, {0, 255, 0});
  const std::vector<std::pair<std::string, const Image8*>> tiles{
      {"a label far too long for a sixty pixel cell", &big}, {"s", &small}};
  const Image8 sheet = contact_sheet(tiles, 2);
  EXPECT_EQ(sheet.width, 2 * 60 + 3 * 8);
  EXPECT_EQ(sheet.height, 14 + 4 + 40 + 2 * 8);
  // The small image is centred across its cell, under the label.
  const int cell_x = 8 + 60 + 8;
  EXPECT_EQ(sheet.at(cell_x + 20, 8 + 18), small.at(0, 0));
  EXPECT_EQ(sheet.at(cell_x + 39, 8 + 27), small.at(0, 0));
  EXPECT_EQ(sheet.at(cell_x + 19, 8 + 18), sheet.at(0, 0));
  // The long label stays in its cell: the gap between the cells is untouched.
  for (int y = 8; y < 8 + 14; ++y) {
    for (int x = 8 + 60; x < cell_x; ++x)
      EXPECT_EQ(sheet.at(x, y), sheet.at(0, 0)) << x << "," << y;
  }
  // But it is drawn (cut, with an ellipsis).
  const Image8 plain = contact_sheet({{"", &big}, {"s", &small}}, 2);
  EXPECT_GT(count_differences(sheet, plain), 20);
}

TEST(ContactSheet, TitleAboveAndFooterBelow) {
  const Image8 a(40, 30, {200, 0, 0}), footer(300, 20, {0, 200, 0});
  const Image8 plain = contact_sheet({{"a", &a}}, 3);
  const Image8 sheet = contact_sheet({{"a", &a}}, 3, {"title", "second line"}, &footer);
  // Title lines of 18 and 14 pixels (each + 2) and a gap of 8; the footer 8 below the grid.
  const int title = 18 + 2 + 14 + 2 + 8;
  EXPECT_EQ(sheet.height, title + plain.height + footer.height + 8);
  EXPECT_EQ(sheet.width, 300 + 2 * 8);  // widened to the footer
  EXPECT_EQ(sheet.at(8, title + 8 + 18), a.at(0, 0));
  EXPECT_EQ(sheet.at(8, title + plain.height), footer.at(0, 0));
  // The title is drawn.
  int lit = 0;
  for (int x = 0; x < sheet.width; ++x) lit += sheet.at(x, 8 + 9) != sheet.at(0, 0) ? 1 : 0;
  EXPECT_GT(lit, 5);
}

// ---- error_map, heat_legend ----

TEST(ErrorMap, NoObjectZeroAndErrorsAllDistinct) {
  const std::vector<double> error{0, 0, 1, 40, kNaN, 2};
  const std::vector<std::uint8_t> object{0, 1, 1, 1, 1, 0};
  const Image8 map = error_map(error, object, 3, 2, 40.0);
  EXPECT_EQ(map.width, 3);  // no colour bar: the size of the image measured
  EXPECT_EQ(map.height, 2);
  EXPECT_EQ(map.at(0, 0), kErrorMapBackground);
  EXPECT_EQ(map.at(1, 0), kErrorMapZero);
  EXPECT_NE(kErrorMapZero, kErrorMapBackground);
  // 1 LSB of 40 is not near-black: the ramp starts at kErrorMapLow, above the zero colour.
  EXPECT_EQ(map.at(2, 0), heat_colour(kErrorMapLow + (1 - kErrorMapLow) / 40));
  EXPECT_NE(map.at(2, 0), kErrorMapZero);
  EXPECT_EQ(map.at(0, 1), heat_colour(1.0));
  EXPECT_EQ(map.at(1, 1), kHeatNan);
  EXPECT_EQ(map.at(2, 1), error_colour(2, 40));  // an error shows even where no object is
  EXPECT_THROW(error_map(error, object, 2, 2, 40.0), std::invalid_argument);
  EXPECT_THROW(error_map(error, {1}, 3, 2, 40.0), std::invalid_argument);
  EXPECT_THROW(error_map(error, object, 3, 2, 0.0), std::invalid_argument);
}

TEST(HeatLegend, BarRunsFromZeroToTheScale) {
  const Image8 legend = heat_legend(400, 30, "error, 8-bit LSB");
  EXPECT_EQ(legend.width, 400);
  // Somewhere a row holds the zero colour at its left end and the top colour further right.
  bool found = false;
  for (int y = 0; y < legend.height && !found; ++y) {
    if (legend.at(9, y) != kErrorMapZero) continue;
    for (int x = 10; x < legend.width; ++x) found = found || legend.at(x, y) == heat_colour(1.0);
  }
  EXPECT_TRUE(found);
  EXPECT_THROW(heat_legend(100, 30, "t"), std::invalid_argument);
  EXPECT_THROW(heat_legend(400, 0, "t"), std::invalid_argument);
}

TEST(ContactSheet, RejectsBadArguments) {
  const Image8 image(4, 4);
  EXPECT_THROW(contact_sheet({}, 2), std::invalid_argument);
  EXPECT_THROW(contact_sheet({{"a", &image}}, 0), std::invalid_argument);
  EXPECT_THROW(contact_sheet({{"a", nullptr}}, 1), std::invalid_argument);
}

// ---- demo images, to look at: GLINT_IMAGE_DEMO=/tmp/image_demo test_image --gtest_filter=Demo.*
// --

TEST(Demo, WritesImagesToLookAt) {
  const char* dir = std::getenv("GLINT_IMAGE_DEMO");
  if (!dir || !*dir) GTEST_SKIP() << "set GLINT_IMAGE_DEMO=DIR to write the demo images";
  std::filesystem::create_directories(dir);
  const std::string out = dir;

  const int w = 256, h = 160;
  std::vector<double> ramp(w * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) ramp[y * w + x] = 2.0 * x / (w - 1);
  }
  const Image8 heat = heatmap_with_scale(ramp, w, h, 2.0, "gradient 0..2 LSB, left to right");
  write_png(out + "/heatmap_gradient.png", heat);

  // A small map with NaNs and a scale that is not round.
  std::vector<double> spots(64 * 48);
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const double r = std::hypot(x - 32.0, y - 24.0);
      spots[y * 64 + x] = r < 4 ? kNaN : 1.7 * std::exp(-r * r / 200.0);
    }
  }
  const Image8 small = heatmap_with_scale(spots, 64, 48, 1.7, "schlick n=50 error (8-bit LSB)");
  write_png(out + "/heatmap_small.png", small);

  Image8 ramp_srgb(128, 96);
  for (int y = 0; y < 96; ++y) {
    for (int x = 0; x < 128; ++x) {
      const std::uint8_t v = srgb8(x / 127.0);
      ramp_srgb.set(x, y, {v, srgb8(0.5 * x / 127.0), srgb8(y / 95.0)});
    }
  }
  Image8 colours(128, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 128; ++x) colours.set(x, y, heat_colour(x / 127.0));
  }
  Image8 text(160, 60, {40, 40, 48});
  draw_text(text, 4, 4, "Hello, glint: 0.5 LSB", {255, 255, 255}, 14);
  draw_text(text, 4, 22, "t^n  \xc2\xb1 \xc3\x97 tau=0.87", {255, 200, 80}, 12);
  draw_text(text, 4, 38, "bad \x01\xff bytes", {120, 200, 255}, 16);
  const std::vector<std::pair<std::string, const Image8*>> tiles{
      {"heat map, gradient 0..2", &heat},
      {"srgb8 ramps", &ramp_srgb},
      {"heat_colour 0..1", &colours},
      {"text at 14, 12 and 16 pixels, a label too long for its cell", &text}};
  write_png(out + "/contact_sheet.png", contact_sheet(tiles, 2));

  // Small tiles of two sizes with labels longer than their cells.
  std::vector<Image8> maps;
  for (int i = 0; i < 4; ++i) {
    const int mw = i == 3 ? 64 : 96, mh = i == 3 ? 40 : 64;
    maps.emplace_back(mw, mh);
    for (int y = 0; y < mh; ++y) {
      for (int x = 0; x < mw; ++x) {
        maps.back().set(x, y, heat_colour(std::fabs(std::sin((x + i * 17) * 0.07) * (y + 1)) / mh));
      }
    }
  }
  write_png(out + "/contact_sheet_small.png",
            contact_sheet({{"hast n=50 d=3", &maps[0]},
                           {"schlick n=50 with a very long label", &maps[1]},
                           {"pow (log2/exp2 tables)", &maps[2]},
                           {"lut 64x40", &maps[3]}},
                          2));
}

}  // namespace
}  // namespace glint
