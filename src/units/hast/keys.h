// hast's keys (key_table.h): each declared once; HastConfig takes its defaults from them.
#pragma once

#include <vector>

#include "units/key_table.h"
#include "units/match.h"

namespace glint {

struct HastKeys {
  // "auto" is read by the build: it needs match=minimax, which then picks d per slot.
  static constexpr IntKey d{"d",
                            4,
                            1,
                            16,
                            "exponent: d - 1 multipliers (auto, with match=minimax: per slot, d "
                            "in 1..16 and the root jointly by minimax, the chain as long as the "
                            "largest d; ~0.25 ms per distinct n)",
                            true};
  static constexpr IntKey guard{
      "guard", kAutoInt, 0, 20, "guard bits of the chain (auto: ceil(log2(2d-2)) + 1)", true};
  static constexpr ChoiceKey match{
      "match", "none", kMatchModeNames,
      "root against t^n of the material's n (Gaussian lobes: their equivalent n = "
      "2/omega^2): none (the material's Källberg threshold, or root=) | minimax (the root "
      "minimizing max |f - t^n| on [0, 1]; ~40 us per distinct n) | width (f(t_half) = "
      "1/2 where t_half^n = 1/2: matched half-width, closed form, clamped at 0)",
      false};
  static constexpr RealKey root{
      "root", 0.0, 1.0,
      "explicit root tau in [0, 1) for every slot, as Hast et al. 2003 use it (their "
      "tau = 0.92 for s = 75); not with match=minimax|width"};

  static std::vector<UnitKey> list() { return key_list(d, guard, match, root); }
};

}  // namespace glint
