#include "units/horner/fit_engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "fit/sollya_fit.h"
#include "units/keys.h"
#include "units/memo.h"
#include "units/unit_set.h"

namespace glint {

HornerFitEngine parse_horner_fit_engine(std::string_view text) {
  if (text == "best") return HornerFitEngine::kBest;
  if (text == "glint") return HornerFitEngine::kGlint;
  if (text == "sollya") return HornerFitEngine::kSollya;
  // not from a spec: the key reader accepts HornerKeys::kFits only
  throw std::invalid_argument(fmt::format("horner: unknown fit engine '{}'", text));
}

bool sollya_fits(const HornerFitSpec& spec) {
  return spec.tau_domain && spec.method == FitMethod::kMinimax &&
         spec.degree >= (spec.constrain ? 2 : 1);
}

namespace {

// t^n for a non-integer n has a branch point at t = 0, which is u = -tau/(1 - tau): close to [0, 1]
// when tau is small, where Sollya's supnorm needs seconds to tens of them (n = 1.5, tau = 1e-4,
// degree 10: 12.5 s; n = 5.5, tau = 0.081: 56 ms). Integer n (a polynomial) and tau >= 1/16 stay
// within tens of milliseconds.
bool sollya_practical(double n, double tau) {
  return n == std::floor(n) || tau >= 1.0 / 16;
}

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// What one slot's comparison needs from Sollya: fpminimax's fits at the datapath's fraction bits.
struct Trial {
  std::vector<FixedPointFit> fits;
  bool skipped = false;  // fit=best and Sollya could not win (trial_for): no fits tried
};

// Sollya's certified sup norm of the held polynomial's error (tens of ms; seconds near a branch
// point, which sollya_practical keeps away), once per polynomial and target.
CertifiedSupNorm norm_of(const std::vector<std::int64_t>& raw, int frac, double n, double tau) {
  static Memo<std::tuple<std::vector<std::int64_t>, int, std::uint64_t, std::uint64_t>,
              CertifiedSupNorm>
      memo;
  return memo.get({raw, frac, bits_of(n), bits_of(tau)},
                  [&] { return certified_sup_norm(raw, frac, FitVariable::kU, n, tau); });
}

// fpminimax costs milliseconds to tens of them per fit, and a sweep or a size search builds the
// same slot for many specs: trials are memoized, keyed by everything they depend on (the glint
// fit's coefficients, real and as held, stand for the fit options).
using TrialKey = std::tuple<std::uint64_t, std::uint64_t, int, bool, int,
                            std::vector<std::uint64_t>, std::vector<std::int64_t>, HornerFitEngine>;

// max |clamp(P_q(u), 0, 1) - t(u)^n| on 2^14 + 1 points of u in [0, 1]: the output's error, with
// the clamp the sup norm leaves out (clamp false: without it). P_q in long double (its
// coefficients exactly), t^n in double: powl costs twenty times pow, and these grids ran three
// times per slot.
double grid_error(const HornerUnit& u, double n, bool clamp = true) {
  const std::vector<long double> c = u.real_coefficients();
  const double tau =
      u.coefficients().tau_domain ? input_value(u.scaler().root_raw(), u.config().in) : 0.0;
  constexpr int kPoints = 1 << 14;
  long double worst = 0;
  for (int i = 0; i <= kPoints; ++i) {
    const double v = static_cast<double>(i) / kPoints;
    long double p = 0;
    for (std::size_t k = c.size(); k-- > 0;) p = p * v + c[k];
    if (clamp) p = std::clamp(p, 0.0L, 1.0L);
    const double t = std::min(1.0, tau + (1.0 - tau) * v);
    worst = std::max(worst, std::fabs(p - std::pow(t, n)));
  }
  return static_cast<double>(worst);
}

// The interior local maxima of |P(u) - t(u)^n| on a grid of u (P real, monomial in u), at least
// degree + 1 of them (Chebyshev points make up the count): where fpminimax should pin the error.
std::vector<double> error_extrema(const std::vector<double>& c, double n, double tau, int degree) {
  constexpr int kPoints = 1 << 12;
  std::vector<double> e(kPoints + 1);
  for (int i = 0; i <= kPoints; ++i) {
    const double u = static_cast<double>(i) / kPoints;
    double p = 0;
    for (std::size_t k = c.size(); k-- > 0;) p = p * u + c[k];
    e[static_cast<std::size_t>(i)] = std::fabs(p - std::pow(tau + (1 - tau) * u, n));
  }
  std::vector<double> out;
  for (std::size_t i = 1; i < kPoints; ++i)
    if (e[i] > e[i - 1] && e[i] >= e[i + 1]) out.push_back(static_cast<double>(i) / kPoints);
  for (int k = 0; static_cast<int>(out.size()) <= degree; ++k)
    out.push_back(0.5 - 0.5 * std::cos(M_PI * (k + 0.5) / (degree + 1)));
  std::sort(out.begin(), out.end());
  return out;
}

Trial trial_for(const HornerFitSpec& spec, double n, const HornerUnit& glint) {
  static Memo<TrialKey, Trial> memo;
  const HornerCoefficients& g = glint.coefficients();
  const double tau = glint.scaler().root_raw() >= glint.config().in.raw_one()
                         ? 0.0
                         : input_value(glint.scaler().root_raw(), glint.config().in);
  std::vector<std::uint64_t> start;
  for (double c : g.c) start.push_back(bits_of(c));
  const TrialKey key{
      bits_of(n), bits_of(tau),      spec.degree, spec.constrain, glint.internal_frac(),
      start,      glint.coeff_raw(), spec.engine};
  return memo.get(key, [&] {
    Trial t;
    // fpminimax takes its interpolation points from the extrema of a minimax fit's error: the
    // real minimax fit's where the unit holds it, else (a monotone refit, whose error does not
    // alternate) the local maxima of the held fit's error. One start only: fpminimax near a real
    // minimax fit that needed a monotone refit is rarely monotone itself, and each fit costs tens
    // of ms. The unit proves the result monotone afresh (build_candidate).
    FitOptions o = horner_fit_options(spec, n, tau, 0.0);
    o.monotone = false;
    const FitResult minimax = fit_power(o);
    const std::vector<double>& real = minimax.coeffs;
    // No polynomial of the space does better than the real minimax fit's levelled error (de la
    // Vallée Poussin), nor than the error pinned at u = 0 by P(0) = 0 where t^n = tau^n. Where the
    // fit as held is already within 2^-11 of that floor, Sollya cannot win by more than the sup
    // norm's own enclosure (2^-12) tells apart: skip its fits (tens of ms each).
    const double floor = std::max(minimax.converged ? minimax.levelled_error : 0.0,
                                  g.constrain_zero ? std::pow(tau, n) : 0.0);
    if (spec.engine == HornerFitEngine::kBest &&
        grid_error(glint, n, false) <= floor * (1 + std::ldexp(1.0, -11))) {
      t.skipped = true;
      return t;
    }
    if (real == g.c) {
      t.fits.push_back(fit_power_fixed_point(o, glint.internal_frac(), real));
    } else {
      const std::vector<double> points = error_extrema(g.c, n, tau, spec.degree);
      t.fits.push_back(fit_power_fixed_point(o, glint.internal_frac(), g.c, &points));
    }
    return t;
  });
}

// A Sollya fit as this slot's datapath, or why not (empty unit, reason set).
struct Candidate {
  std::vector<HornerUnit> unit;  // zero or one
  std::string why_not;
};

// The glint fit a Sollya fit must beat (fit=best; none for fit=sollya), with its measures.
struct Rival {
  const HornerUnit* unit = nullptr;
  double grid = 0.0;
};

// Sollya's fit as the slot's datapath if it is valid (and beats the rival, when there is one).
// The cheap tests first: the monotone proofs of a candidate cost as much as the glint unit's own
// (every input code in the worst case), Sollya's sup norm tens of ms.
Candidate build_candidate(const FixedPointFit& fit, const HornerConfig& cfg,
                          const MaterialParams& m, const HornerCoefficients& glint, double tau,
                          int coeff_int, int acc_int, const Rival& rival) {
  Candidate c;
  if (!fit.ok) {
    c.why_not = fit.failure;
    return c;
  }
  HornerCoefficients s = glint;
  s.c = fit.coeffs;
  s.engine = "sollya";
  if (cfg.guard_auto && horner_required_guard(s) > cfg.guard) {
    c.why_not = fmt::format("it needs more guard bits ({}) than the glint fits ({})",
                            horner_required_guard(s), cfg.guard);
    return c;
  }
  try {
    const HornerUnit u(cfg, m, s);
    const double n = m.shininess;
    if (u.coeff_raw() != fit.raw) {
      c.why_not = "its coefficients moved on the datapath's grid";
      return c;
    }
    if (u.coeff_format().int_bits > coeff_int || u.acc_int_bits() > acc_int) {
      c.why_not = "its coefficients need wider registers than the glint fits";
      return c;
    }
    if (rival.unit != nullptr && grid_error(u, n) > rival.grid) {
      c.why_not = "glint's output error is lower";
      return c;
    }
    const CertifiedSupNorm norm = norm_of(fit.raw, u.internal_frac(), n, tau);
    if (!norm.ok) {
      c.why_not = "Sollya could not certify its error";
      return c;
    }
    if (rival.unit != nullptr) {
      const CertifiedSupNorm g =
          norm_of(rival.unit->coeff_raw(), rival.unit->internal_frac(), n, tau);
      if (!g.ok || !(norm.hi < g.lo)) {
        c.why_not = "its error is not certainly lower than glint's";
        return c;
      }
    }
    if (!u.polynomial_monotone() || !u.output_monotone()) {
      c.why_not = "it is not proven monotone";
      return c;
    }
    s.sup_certified = true;
    s.sup_lo = norm.lo;
    s.sup_hi = norm.hi;
    c.unit.emplace_back(cfg, m, s);
  } catch (const std::invalid_argument& e) {
    c.why_not = e.what();
  }
  return c;
}

}  // namespace

void choose_fit_engines(const HornerFitSpec& spec, const HornerConfig& cfg,
                        const std::vector<MaterialParams>& slots,
                        std::vector<HornerCoefficients>& fits, std::vector<HornerUnit>& units) {
  if (spec.engine == HornerFitEngine::kGlint || !sollya_fits(spec)) return;
  // The registers are shared: a Sollya fit may use what the widest glint fit already built.
  int coeff_int = 1, acc_int = 1;
  for (const HornerUnit& u : units) {
    coeff_int = std::max(coeff_int, u.coeff_format().int_bits);
    acc_int = std::max(acc_int, u.acc_int_bits());
  }
  for (std::size_t i = 0; i < units.size(); ++i) {
    for_slot(slots[i], [&] {
      const double n = slots[i].shininess;
      const HornerUnit& held = units[i];
      const double tau = held.scaler().root_raw() >= held.config().in.raw_one()
                             ? 0.0
                             : input_value(held.scaler().root_raw(), held.config().in);
      if (!sollya_practical(n, tau)) {
        if (spec.engine == HornerFitEngine::kBest) return;
        // refusal: horner.fit_sollya_branch
        throw std::invalid_argument(fmt::format(
            "horner: {}: t^{:g} on [{:.4g}, 1]: a non-integer n with tau_q below 1/16 puts t^n's "
            "branch point at t = 0 too close for Sollya's certified sup norm (seconds per fit); "
            "fit=best keeps glint's there",
            key_values({{"fit", "sollya"}}), n, tau));
      }
      const Trial t = trial_for(spec, n, units[i]);
      const HornerCoefficients& glint = units[i].coefficients();
      const bool forced = spec.engine == HornerFitEngine::kSollya;
      Rival rival;
      if (!forced) rival = {&units[i], grid_error(units[i], n)};
      Candidate c;
      for (const FixedPointFit& f : t.fits) {
        c = build_candidate(f, cfg, slots[i], glint, tau, coeff_int, acc_int, rival);
        if (!c.unit.empty()) break;
      }
      if (c.unit.empty()) {
        if (!forced) return;  // glint's stays, as built
        // refusal: horner.fit_sollya
        throw std::invalid_argument(fmt::format(
            "horner: {}: no fpminimax fit of t^{:g} on the datapath's grid "
            "(degree {}, {} fraction bits): {} (fit=best keeps glint's there)",
            key_values({{"fit", "sollya"}}), n, spec.degree, units[i].internal_frac(), c.why_not));
      }
      fits[i] = c.unit.front().coefficients();
      units[i] = std::move(c.unit.front());
    });
  }
}

}  // namespace glint
