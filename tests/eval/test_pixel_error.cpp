// The pixel error (src/reference/pixel_error.h) on hand-checked values, and through the lanes: the
// weighted error is the largest channel's, in the file's display, and --eps-measure channel puts
// that channel's weight in c_y's place in tau.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "eval/evaluate.h"
#include "io/input_error.h"
#include "io/vectors.h"
#include "reference/pixel_error.h"

namespace glint {
namespace {

// A vector file in memory and its reader (which reads from the stream as it goes).
struct Input {
  explicit Input(const std::string& text) : in(text), reader(in, "test.vec") {}
  std::istringstream in;
  VectorReader reader;
};

// One orange light on a white Phong material, and rows across the threshold and the highlight.
std::string orange(const std::string& display_line = "") {
  std::string text = "glint-vectors 1\neps 1e-3\n" + display_line +
                     "lights 1\nlight 0 1,0.5,0.1\n"
                     "material white specular=1,1,1 lobe=phong shininess=50\n"
                     "columns t material\ndata\n";
  for (int k = 0; k <= 200; ++k) text += std::to_string(0.8 + 0.001 * k) + " white\n";
  return text;
}

TEST(PixelError, ByHand) {
  const Rgb w = channel_weights(Rgb{1, 0.5, 0.1}, Rgb{1, 1, 1});
  EXPECT_DOUBLE_EQ(largest_channel(w), 1.0);
  // Linear: the largest channel's weight times the scalar error.
  EXPECT_DOUBLE_EQ(request_pixel_error(DisplayEncoding::kLinear8, w, 0.5, 0.25), 0.25);
  // sRGB over black, a skipped lobe of 1e-3: the toe's 12.92 (3.29 LSB at 8 bits).
  EXPECT_DOUBLE_EQ(request_pixel_error(DisplayEncoding::kSrgb8, Rgb{1, 1, 1}, 0, 1e-3), 12.92e-3);
  // A bright channel saturates (sRGB clamps at 1) and shows nothing of the difference, while a
  // dimmer one shows it: the largest channel is not always the largest weight's.
  const Rgb two{2, 1, 0};
  const double green = encode(DisplayEncoding::kSrgb8, 0.6) - encode(DisplayEncoding::kSrgb8, 0.5);
  ASSERT_GT(green, 0.06);
  EXPECT_DOUBLE_EQ(request_pixel_error(DisplayEncoding::kSrgb8, two, 0.6, 0.5), green);
  // The bound: slope x weight x scalar bound, at most full scale for sRGB.
  EXPECT_DOUBLE_EQ(pixel_error_bound(DisplayEncoding::kLinear8, 0.5, 0.1), 0.05);
  EXPECT_DOUBLE_EQ(pixel_error_bound(DisplayEncoding::kSrgb8, 0.5, 0.1), 0.646);
  EXPECT_DOUBLE_EQ(pixel_error_bound(DisplayEncoding::kSrgb8, 1, 1), 1.0);
  // The codes: sRGB as image/srgb8 always gave them, linear rounded half up.
  EXPECT_EQ(display_code8(DisplayEncoding::kSrgb8, 1e-3), 3);
  EXPECT_EQ(display_code8(DisplayEncoding::kLinear8, 1e-3), 0);
  EXPECT_EQ(display_code8(DisplayEncoding::kLinear8, 0.5), 128);
  EXPECT_EQ(display_code8(DisplayEncoding::kLinear8, std::nan("")), 0);
  // Eps's weight: c_y (eq.3) by default, the largest channel on request.
  EXPECT_DOUBLE_EQ(threshold_weight(EpsMeasure::kLuminance, Rgb{1, 0.5, 0.1}, Rgb{1, 1, 1}),
                   0.2126 + 0.7152 * 0.5 + 0.0722 * 0.1);
  EXPECT_DOUBLE_EQ(threshold_weight(EpsMeasure::kChannel, Rgb{1, 0.5, 0.1}, Rgb{1, 1, 1}), 1.0);
}

// Under the orange light the weighted error is the red channel's, 1.73 times what c_y gave.
TEST(PixelError, WeightedIsTheLargestChannel) {
  for (const char* spec : {"pow", "hast", "lut:bits=4"}) {
    Input input(orange());
    VectorReader& reader = input.reader;
    Evaluator ev(reader.header(), {parse_unit_spec(spec)});
    VectorRow row;
    while (reader.next(row)) ev.add(row);
    const UnitStats s = ev.stats().at(0);
    ASSERT_GT(s.total.max_abs, 0) << spec;
    // One slot of weight 1 (red): the weighted maximum is the scalar one, where c_y's was 0.577x.
    EXPECT_EQ(ev.slots().pixel_weight_max.at(0), 1.0);
    EXPECT_DOUBLE_EQ(s.weighted.max_abs, s.total.max_abs) << spec;
    EXPECT_DOUBLE_EQ(s.slots.at(0).weight, 1.0) << spec;
    EXPECT_DOUBLE_EQ(s.weighted_bound(), s.bound().total()) << spec;
  }
}

// `display srgb8`: the weighted error through the sRGB transfer, the engine (add_rows, which
// defers references) and the row-at-a-time path alike.
TEST(PixelError, SrgbDisplayThroughBothPaths) {
  Input input(orange("display srgb8\n"));
  VectorReader& a = input.reader;
  ASSERT_EQ(a.header().display, DisplayEncoding::kSrgb8);
  Evaluator by_row(a.header(), {parse_unit_spec("hast")});
  std::vector<VectorRow> rows;
  for (VectorRow row; a.next(row);) rows.push_back(row);
  for (const VectorRow& row : rows) by_row.add(row);
  Evaluator engine(a.header(), {parse_unit_spec("hast")});
  engine.add_rows(rows.data(), rows.size(), 2);
  const UnitStats r = by_row.stats().at(0), e = engine.stats().at(0);
  EXPECT_EQ(r.weighted.max_abs, e.weighted.max_abs);
  EXPECT_EQ(r.weighted.t_at_max, e.weighted.t_at_max);
  // Not the linear figure: the same rows through the linear display give another maximum.
  Input linear_input(orange());
  Evaluator linear(linear_input.reader.header(), {parse_unit_spec("hast")});
  linear.add_rows(rows.data(), rows.size(), 2);
  EXPECT_NE(linear.stats().at(0).weighted.max_abs, r.weighted.max_abs);
  EXPECT_EQ(linear.stats().at(0).total.max_abs, r.total.max_abs);  // the scalar error is the same
  // Its bound: the toe's slope over the linear bound, clamped to full scale.
  EXPECT_DOUBLE_EQ(r.weighted_bound(), std::min(1.0, 12.92 * r.bound().total()));
  EXPECT_LE(r.weighted.max_abs, r.weighted_bound());
}

// --eps-measure channel: tau from the red weight (1) instead of c_y (0.577): a lower threshold,
// and the skip part of the pixel error within eps.
TEST(PixelError, ChannelEpsMeasureLowersTau) {
  Input input(orange());
  VectorReader& a = input.reader;
  const SlotMap lum = make_slots(a.header());
  const SlotMap chan = make_slots(with_eps_measure(a.header(), EpsMeasure::kChannel));
  EXPECT_EQ(lum.eps_measure, EpsMeasure::kLuminance);
  EXPECT_EQ(chan.eps_measure, EpsMeasure::kChannel);
  const double cy = 0.2126 + 0.7152 * 0.5 + 0.0722 * 0.1;
  EXPECT_NEAR(lum.params.at(0).tau, std::pow(1e-3 / cy, 1.0 / 50), 1e-12);
  EXPECT_DOUBLE_EQ(chan.params.at(0).tau, std::pow(1e-3, 1.0 / 50));
  EXPECT_NEAR(lum.skip_ratio, 1 / cy, 1e-12);
  EXPECT_EQ(chan.skip_ratio, 1.0);
  // The skip part on the pixel: level x weight, eps / c_y x 1 against eps.
  EXPECT_NEAR(lum.params.at(0).level * lum.pixel_weight_max.at(0), 1e-3 / cy, 1e-15);
  EXPECT_NEAR(chan.params.at(0).level * chan.pixel_weight_max.at(0), 1e-3, 1e-15);
}

// The header's `display` line: once, linear8 or srgb8, written back only when not the default.
TEST(PixelError, DisplayLine) {
  EXPECT_EQ(Input(orange()).reader.header().display, DisplayEncoding::kLinear8);
  EXPECT_EQ(Input(orange("display linear8\n")).reader.header().display, DisplayEncoding::kLinear8);
  try {
    Input bad(orange("display gamma22\n"));
    FAIL() << "a bad display was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3u);
    EXPECT_EQ(e.field(), "display");
  }
  EXPECT_THROW(Input(orange("display srgb8\ndisplay srgb8\n")), InputError);
  for (const DisplayEncoding d : {DisplayEncoding::kLinear8, DisplayEncoding::kSrgb8}) {
    VectorHeader h = Input(orange()).reader.header();
    h.display = d;
    std::ostringstream out;
    {
      VectorWriter w(out, h, "out.vec");
      w.commit();
    }
    EXPECT_EQ(out.str().find("display") != std::string::npos, d == DisplayEncoding::kSrgb8);
    EXPECT_EQ(Input(out.str()).reader.header().display, d);
  }
}

}  // namespace
}  // namespace glint
