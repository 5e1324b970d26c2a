// schlick's keys (key_table.h): each declared once; SchlickConfig takes its defaults from them.
#pragma once

#include <string_view>
#include <vector>

#include "units/key_table.h"
#include "units/match.h"

namespace glint {

struct SchlickKeys {
  // n <= 16383.9375 in steps of 1/16.
  static constexpr FormatKey n{"n", uq(14, 4), "shininess register format (holds n')"};
  static constexpr ChoiceKey match{
      "match", "none", kMatchModeNames,
      "n' in S = t/(n' - n' t + t), against t^n of the material's n (Gaussian lobes: their "
      "equivalent n = 2/omega^2): none (n' = n, as Schlick 1994) | minimax (n' minimizing "
      "max |S - t^n| on [0, 1]; ~30 us per distinct n) | width (S(t_half) = 1/2 where "
      "t_half^n = 1/2: matched half-width, n' = t_half/(1 - t_half))",
      false};
  static constexpr std::string_view kDividers[] = {"pipelined", "iterative"};
  static constexpr ChoiceKey divider{
      "divider", "pipelined", kDividers,
      "divider kind (timing): pipelined (one quotient bit per stage, II 1) | "
      "iterative (radix-2, one quotient bit per cycle, II = quotient bits)"};

  static std::vector<UnitKey> list() { return key_list(n, match, divider); }
};

}  // namespace glint
