// glint's model of the Tesla-class SFU (src/units/sfu/tesla_sfu.h) against reference vectors made
// from envytools' bit-exact model of the hardware (tests/units/data/README.md): every line, every
// intermediate, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "units/sfu/tesla_sfu.h"

namespace glint::tesla_sfu {
namespace {

const std::string kVectors = GLINT_SOURCE_DIR "/tests/units/data/tesla_sfu_vectors.txt";

struct Line {
  int number = 0;
  std::string op;
  std::vector<std::uint32_t> words;
};

std::vector<Line> read_vectors(const std::string& op) {
  std::ifstream in(kVectors);
  EXPECT_TRUE(in) << kVectors;
  std::vector<Line> out;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    if (text.empty() || text[0] == '#') continue;
    std::istringstream fields(text);
    Line l;
    l.number = number;
    fields >> l.op;
    if (l.op != op) continue;
    std::string w;
    while (fields >> w) l.words.push_back(static_cast<std::uint32_t>(std::stoul(w, nullptr, 16)));
    out.push_back(l);
  }
  return out;
}

std::string hex(std::uint32_t v) {
  std::ostringstream os;
  os << std::hex << v;
  return os.str();
}

float as_float(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

TEST(TeslaSfu, Lg2MatchesTheHardwareModel) {
  const auto lines = read_vectors("lg2");
  ASSERT_EQ(lines.size(), 5450u);
  int failures = 0;
  for (const Line& l : lines) {
    ASSERT_EQ(l.words.size(), 2u) << "line " << l.number;
    const std::uint32_t got = lg2(l.words[0]);
    if (got != l.words[1] && ++failures <= 10)
      ADD_FAILURE() << "line " << l.number << ": lg2(" << hex(l.words[0]) << ") = " << hex(got)
                    << ", hardware " << hex(l.words[1]);
  }
  EXPECT_EQ(failures, 0);
}

TEST(TeslaSfu, Ex2AndItsRangeReductionMatchTheHardwareModel) {
  const auto lines = read_vectors("ex2");
  ASSERT_EQ(lines.size(), 3213u);
  int failures = 0;
  for (const Line& l : lines) {
    ASSERT_EQ(l.words.size(), 3u) << "line " << l.number;
    const std::uint32_t pre = pre_ex2(l.words[0]), got = ex2(l.words[1]);
    if ((pre != l.words[1] || got != l.words[2]) && ++failures <= 10)
      ADD_FAILURE() << "line " << l.number << ": pre_ex2(" << hex(l.words[0]) << ") = " << hex(pre)
                    << " (hardware " << hex(l.words[1]) << "), ex2 = " << hex(got) << " (hardware "
                    << hex(l.words[2]) << ")";
  }
  EXPECT_EQ(failures, 0);
}

TEST(TeslaSfu, HighlightMatchesTheShaderOnTheHardwareModel) {
  const auto lines = read_vectors("pow");
  ASSERT_EQ(lines.size(), 1596u);
  int failures = 0;
  for (const Line& l : lines) {
    ASSERT_EQ(l.words.size(), 6u) << "line " << l.number;
    const Highlight h = highlight(l.words[0], l.words[1]);
    const bool same = h.lg2 == l.words[2] && h.product == l.words[3] && h.pre == l.words[4] &&
                      h.ex2 == l.words[5];
    if (!same && ++failures <= 10)
      ADD_FAILURE() << "line " << l.number << ": t " << hex(l.words[0]) << " n " << hex(l.words[1])
                    << ": lg2 " << hex(h.lg2) << " product " << hex(h.product) << " pre "
                    << hex(h.pre) << " ex2 " << hex(h.ex2) << "; hardware " << hex(l.words[2])
                    << " " << hex(l.words[3]) << " " << hex(l.words[4]) << " " << hex(l.words[5]);
  }
  EXPECT_EQ(failures, 0);
}

// The vectors pin every table entry: changing any coefficient of any segment by one changes at
// least one expected output (so a wrong entry cannot hide between the vectors' points).
template <typename Eval>
void every_entry_matters(const Table& hardware, const std::vector<std::uint32_t>& inputs,
                         Eval eval) {
  std::vector<std::uint32_t> want;
  for (std::uint32_t x : inputs) want.push_back(eval(x, hardware));
  int unpinned = 0;
  for (int segment = 0; segment < kSegments; ++segment) {
    for (std::int32_t Coefficients::*field :
         {&Coefficients::a, &Coefficients::b, &Coefficients::c}) {
      for (int delta : {-1, 1}) {
        Table changed = hardware;
        changed[segment].*field += delta;
        bool seen = false;
        for (std::size_t i = 0; i < inputs.size() && !seen; ++i)
          seen = eval(inputs[i], changed) != want[i];
        if (!seen && ++unpinned <= 10)
          ADD_FAILURE() << "segment " << segment << ", coefficient "
                        << (field == &Coefficients::a   ? "A"
                            : field == &Coefficients::b ? "B"
                                                        : "C")
                        << ": a change of " << delta
                        << " in a coefficient changes no vector's output";
      }
    }
  }
  EXPECT_EQ(unpinned, 0);
}

TEST(TeslaSfu, VectorsPinEveryLg2TableEntry) {
  std::vector<std::uint32_t> inputs;
  for (const Line& l : read_vectors("lg2")) inputs.push_back(l.words[0]);
  every_entry_matters(kLg2Table, inputs,
                      [](std::uint32_t x, const Table& table) { return lg2(x, table); });
}

TEST(TeslaSfu, VectorsPinEveryEx2TableEntry) {
  std::vector<std::uint32_t> inputs;
  for (const Line& l : read_vectors("ex2")) inputs.push_back(l.words[1]);  // pre_ex2's output
  every_entry_matters(kEx2Table, inputs,
                      [](std::uint32_t p, const Table& table) { return ex2(p, table); });
}

// What the vectors cannot show: the model is the hardware's own accuracy, near but not at t^n.
// lg2's error (a few 1e-8 absolute) is multiplied by n before ex2, so the highlight's relative
// error grows with n: 3.5e-5 at worst here for n up to 500 (where t^n is above 2^-24).
TEST(TeslaSfu, HighlightIsCloseToThePower) {
  double worst = 0;
  for (double n : {1.0, 5.0, 50.0, 500.0}) {
    for (int c = 1; c <= 32768; c += 7) {
      const double t = c / 32768.0;
      const double want = std::pow(t, n);
      if (want < std::ldexp(1.0, -24)) continue;
      std::uint32_t tb, nb;
      const float tf = static_cast<float>(t), nf = static_cast<float>(n);
      std::memcpy(&tb, &tf, 4);
      std::memcpy(&nb, &nf, 4);
      const double got = as_float(highlight(tb, nb).ex2);
      worst = std::max(worst, std::fabs(got - want) / want);
    }
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(worst, 0.0);  // not the float pow in disguise
}

}  // namespace
}  // namespace glint::tesla_sfu
