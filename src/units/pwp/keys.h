// pwp's keys (key_table.h): each declared once; PwpConfig takes its defaults from them.
#pragma once

#include <string_view>
#include <vector>

#include "units/key_table.h"

namespace glint {

struct PwpKeys {
  static constexpr IntKey segments{
      "segments", 4, 0, 10,
      "log2 of the segment count K over [t0, 1] (the index: the top bits of t - t0)"};
  static constexpr IntKey degree{"degree", 2, 1, 3,
                                 "polynomial degree per segment, in the offset below the index"};
  static constexpr IntKey coef_frac{
      "coef_frac", kAutoInt, 1, 40, "coefficient fraction bits (auto: out + 2)", true};
  static constexpr IntKey guard{
      "guard",
      kAutoInt,
      0,
      24,
      "accumulator bits below the output's LSB (auto: faithful, at least coef_frac - out, "
      "raised until the output is monotone)",
      true};

  // domain=log: units/pwp/log_datapath.h (material-independent lg2 and ex2 tables, n per slot).
  static constexpr std::string_view kDomains[] = {"t", "log"};
  static constexpr ChoiceKey domain{
      "domain", "t", kDomains,
      "t: t^n by segments of t, one table per material | log: ex2(n lg2 t), lg2 and ex2 by "
      "segments of the mantissa and of y's fraction, tables shared by every material, n in a "
      "register (widths from out, n and degree; coef_frac, guard and fit are domain=t's)",
      false};
  static constexpr FormatKey n{"n", uq(10, 4), "shininess register format (domain=log only)"};
  static constexpr std::string_view kFits[] = {"best", "glint", "sollya"};
  static constexpr ChoiceKey fit{
      "fit", "best", kFits,
      "segment coefficients (degree >= 2): best (per segment, Sollya's where its certified error "
      "is lower) | glint (Remez, rounded to nearest) | sollya (fpminimax on the coefficients' "
      "grid wherever it is valid)",
      false};

  static std::vector<UnitKey> list() {
    return key_list(segments, degree, coef_frac, guard, fit, domain, n);
  }
};

}  // namespace glint
