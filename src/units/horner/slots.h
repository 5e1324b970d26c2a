// The horner unit's per-datapath build: one fit per datapath group (units/slot_plan.h; the
// "slots" below are the groups' params) on the domain the hardware evaluates, the
// shared guard, and the monotonicity repair (horner.cpp calls it; datapath.h has the budget).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "fit/fit.h"
#include "units/common.h"
#include "units/horner/datapath.h"

namespace glint {

// Key fit: which coefficients a slot keeps (fit_engine.h).
enum class HornerFitEngine : std::uint8_t { kBest, kGlint, kSollya };
HornerFitEngine parse_horner_fit_engine(std::string_view text);

// Every field but engine (the choice made after fitting, fit_engine.h) is part of fit_slot's memo
// key (slots.cpp): a new field goes there too.
struct HornerFitSpec {
  int degree = HornerKeys::degree.def;
  FitMethod method = FitMethod::kMinimax;
  bool tau_domain = HornerKeys::domain.def == "tau";
  bool constrain = HornerKeys::constrain.def;
  HornerFitEngine engine = HornerFitEngine::kBest;
};
static_assert(HornerKeys::fit.def == "best", "HornerFitSpec::engine is the key's default");
static_assert(HornerKeys::method.def == "minimax", "HornerFitSpec::method is the key's default");

// The lower end of a slot's fit domain: tau_q, the value of the u scaler's root code
// (root_threshold_raw), so that the fitted polynomial's u is the hardware's; 0 on the full domain
// and for slots whose root is at 1 (always skipped: u = 0 on every code).
double horner_fit_tau(const MaterialParams& m, const QFormat& in, bool tau_domain);

// The fit of t^n for one slot: monotone (with P' >= min_slope), on [tau, 1] in u or on (0, 1].
FitOptions horner_fit_options(const HornerFitSpec& spec, double n, double tau, double min_slope);

// fit_power(horner_fit_options(...))'s coefficients, memoized per process (bounded, thread-safe).
HornerCoefficients fit_slot(const HornerFitSpec& spec, double n, double tau, double min_slope);

// Builds every slot's datapath at cfg.guard (< 0: auto, the largest guard any slot needs for a
// faithful result, written back into cfg). Every datapath is monotone: its quantized polynomial
// and its output on every input code (HornerUnit::polynomial_monotone, output_monotone); a slot
// that fails either is refitted in the Bernstein cone with a step margin that makes both hold by
// construction. Throws std::invalid_argument (naming the slot) when no such margin exists.
std::vector<HornerUnit> build_horner_slots(const HornerFitSpec& spec, HornerConfig& cfg,
                                           const std::vector<MaterialParams>& slots);

}  // namespace glint
