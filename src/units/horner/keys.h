// horner's keys (key_table.h): each declared once; HornerConfig and HornerFitSpec take their
// defaults from them.
#pragma once

#include <string_view>
#include <vector>

#include "units/key_table.h"

namespace glint {

struct HornerKeys {
  static constexpr IntKey degree{"degree", 4, 1, 10, "polynomial degree p (1..10)"};
  static constexpr std::string_view kMethods[] = {"ls", "robust", "minimax"};
  static constexpr ChoiceKey method{
      "method", "minimax", kMethods,
      "fit: ls | robust (Öztürk's bisquare weights, for noisy measured data: on t^n "
      "itself they can reject the highlight, and the build warns) | minimax (Remez); "
      "each made monotone"};
  static constexpr std::string_view kDomains[] = {"tau", "full"};
  static constexpr ChoiceKey domain{
      "domain", "tau", kDomains,
      "fit domain: tau ([tau_q, 1], u = (t-tau_q)/(1-tau_q), tau_q the root code) | full"};
  static constexpr FlagKey constrain{"constrain", true,
                                     "on: P(1) = 1 and, on the tau domain, P(tau) = 0"};
  static constexpr std::string_view kFits[] = {"best", "glint", "sollya"};
  static constexpr ChoiceKey fit{
      "fit", "best", kFits,
      "coefficients: best (of glint and sollya, per slot: the lower error after rounding) | "
      "glint (the method's fit, rounded to nearest) | sollya (fpminimax on the coefficients' "
      "grid; method=minimax, domain=tau only)",
      false};
  static constexpr IntKey guard{
      "guard", kAutoInt, 0, 20, "guard bits (auto: faithful bound from the coefficients)", true};

  static std::vector<UnitKey> list() {
    return key_list(degree, method, domain, constrain, fit, guard);
  }
};

}  // namespace glint
