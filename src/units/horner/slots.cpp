#include "units/horner/slots.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "units/horner/fit_engine.h"
#include "units/keys.h"
#include "units/memo.h"
#include "units/unit_set.h"
#include "units/warning.h"

namespace glint {

namespace {

// Remez search grid on the tau domain: t^n in u on [tau_q, 1] is close to an exponential in u
// (rate ln(c_y / eps) <= ~14), smooth enough that 24 points per unknown locate every sign run of
// the error; golden-section search then refines each extremum. The full domain keeps fit.h's
// dense default (t^n on (0, 1] is a spike at 1 for large n).
int remez_grid(const HornerFitSpec& spec) {
  return spec.tau_domain ? 24 * (spec.degree + 2) + 1 : 0;
}

}  // namespace

FitOptions horner_fit_options(const HornerFitSpec& spec, double n, double tau, double min_slope) {
  FitOptions o;
  o.shininess = n;
  o.degree = spec.degree;
  o.method = spec.method;
  o.domain = spec.tau_domain ? FitDomain::kTau : FitDomain::kFull;
  o.tau = tau;
  o.constrain_one = spec.constrain;
  o.constrain_zero = spec.constrain && spec.tau_domain;
  o.monotone = true;
  o.min_slope = min_slope;
  o.remez_grid = remez_grid(spec);
  o.error_grid = 0;  // the unit reports its errors itself
  return o;
}

namespace {

// A fit is a pure function of its spec, n, tau and slope margin, and a monotone Remez fit costs
// milliseconds. A sweep builds the same fit for every format that keeps tau_q (every format on the
// full domain, where tau is 0), and a --grid's value check builds each value once more: one memo
// per process. Doubles are keyed by their bits (a NaN would break a map's ordering). Bounded: a
// long sweep or fuzz run that fills it starts it afresh, so memory stays ~1 MB.
using FitKey = std::tuple<int, FitMethod, bool, bool, std::uint64_t, std::uint64_t, std::uint64_t>;

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

}  // namespace

HornerCoefficients fit_slot(const HornerFitSpec& spec, double n, double tau, double min_slope) {
  static Memo<FitKey, HornerCoefficients> memo;
  const FitKey key{spec.degree, spec.method,  spec.tau_domain,   spec.constrain,
                   bits_of(n),  bits_of(tau), bits_of(min_slope)};
  return memo.get(key, [&] {
    const FitOptions o = horner_fit_options(spec, n, tau, min_slope);
    const FitResult r = fit_power(o);
    HornerCoefficients c{r.coeffs, spec.tau_domain, o.constrain_one, o.constrain_zero};
    c.sample_max_error = r.sample_max_error;
    c.ls_sample_max_error = r.ls_sample_max_error;
    c.robust_rejects = robust_rejects_samples(r);
    return c;
  });
}

namespace {

// The slope margin of a refit (fit_monotone proves P' >= it on [0, 1]). Quantizing the
// coefficients (½ LSB each, and the P(1) = 1 repair's sum of them in one coefficient) moves P' by
// at most (p (p + 1) / 2 + p) 2^-(fh+1); the output proof needs P_q' >= 2E / dmin
// (horner_monotone.cpp). Half as much again for margin.
double slope_margin(const HornerUnit& u, int degree) {
  const double p = degree;
  const double lsb = std::ldexp(1.0, -u.internal_frac());
  const double step = std::ldexp(static_cast<double>(u.scaler().k_raw()),
                                 -(u.config().in.frac_bits + u.scaler().k_frac()));
  const double dmin = std::max(lsb, step - lsb);
  const double e = (p - 1) * 0.5 * lsb;
  const double quant = (p * (p + 1) / 2 + p) * 0.5 * lsb;
  return 1.5 * (2 * e / dmin + quant);
}

}  // namespace

namespace {

// method=robust fits t^n itself, where there is no noise for bisquare weights to reject: name the
// slot where they threw the most of the highlight away, once per message.
void warn_robust(const HornerFitSpec& spec, const std::vector<MaterialParams>& slots,
                 const std::vector<HornerCoefficients>& fits) {
  std::size_t worst = fits.size();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const auto loss = [&](std::size_t k) {
      return fits[k].sample_max_error - fits[k].ls_sample_max_error;
    };
    if (fits[i].robust_rejects && (worst == fits.size() || loss(i) > loss(worst))) worst = i;
  }
  if (worst == fits.size()) return;
  const HornerCoefficients& f = fits[worst];
  warn_once(fmt::format(
      "unit 'horner': key 'method' = 'robust' (degree {}, domain {}): the fit of t^{:g}{} has a "
      "largest error of {:.4g} on its samples against {:.4g} for method=ls: on noise-free t^n "
      "the bisquare weights reject its steepest part (the highlight, or t near 0 for n < 1) as "
      "outliers; use method=minimax or ls (robust is for noisy, measured data)",
      spec.degree, spec.tau_domain ? "tau" : "full", slots[worst].shininess,
      slots[worst].name.empty() ? "" : " (" + slots[worst].name + ")", f.sample_max_error,
      f.ls_sample_max_error));
}

}  // namespace

double horner_fit_tau(const MaterialParams& m, const QFormat& in, bool tau_domain) {
  if (!tau_domain) return 0.0;
  const std::int64_t root = root_threshold_raw(m, in);
  return root >= in.raw_one() ? 0.0 : input_value(root, in);
}

std::vector<HornerUnit> build_horner_slots(const HornerFitSpec& spec, HornerConfig& cfg,
                                           const std::vector<MaterialParams>& slots) {
  // Slots with the same (n, tau_q) share one fit through fit_slot's memo.
  std::vector<HornerCoefficients> fits;
  fits.reserve(slots.size());
  for (const MaterialParams& m : slots) {
    const double tau = horner_fit_tau(m, cfg.in, spec.tau_domain);
    fits.push_back(for_slot(m, [&] { return fit_slot(spec, m.shininess, tau, 0); }));
  }
  const bool auto_guard = cfg.guard < 0;
  int extra = 0;  // guard bits added because a slot's output could not be made monotone
  for (int attempt = 0;; ++attempt) {
    HornerConfig c = cfg;
    c.guard_auto = auto_guard;
    int max_guard = 64;
    if (auto_guard) {
      // The datapath width is shared: the guard is the largest any slot needs.
      int preferred = 0, required = 0;
      for (std::size_t i = 0; i < slots.size(); ++i) {
        preferred = std::max(preferred, horner_preferred_guard(fits[i]));
        required = std::max(required, horner_required_guard(fits[i]));
        max_guard = std::min(max_guard, horner_max_guard(fits[i], slots[i], c.in, c.out));
      }
      c.guard = std::max(required, std::min(preferred, max_guard)) + extra;
    }
    std::vector<HornerUnit> units;
    units.reserve(slots.size());
    bool regrow = false, widen = false;
    for (std::size_t i = 0; i < slots.size() && !widen; ++i) {
      const MaterialParams& m = slots[i];
      for_slot(m, [&] {
        HornerUnit u(c, m, fits[i]);
        if (u.polynomial_monotone() && u.output_monotone()) {
          units.push_back(std::move(u));
          return;
        }
        const double slope = slope_margin(u, spec.degree);
        if (slope < 1.0) {
          HornerCoefficients refit =
              fit_slot(spec, m.shininess, horner_fit_tau(m, c.in, spec.tau_domain), slope);
          HornerUnit r(c, m, refit);
          if (r.polynomial_monotone() && r.output_monotone()) {
            fits[i] = std::move(refit);
            regrow = regrow || (auto_guard && horner_required_guard(fits[i]) > c.guard);
            units.push_back(std::move(r));
            return;
          }
        }
        // The inner roundings are too coarse against the output's step per input code (an
        // input format finer than u, or a slope margin no fit can give): more guard bits.
        if (auto_guard && c.guard < max_guard) {
          widen = true;
          return;
        }
        // refusal: horner.monotone
        throw std::invalid_argument(fmt::format(
            "horner: {}: no monotone degree-{} output at {} guard bits with input {} (a slope "
            "margin of {:.3g} would be needed; more guard bits or a coarser input)",
            key_values({{"guard", auto_value(!auto_guard, c.guard)},
                        {"in", c.in.name()},
                        {"degree", std::to_string(spec.degree)}}),
            spec.degree, c.guard, c.in.name(), slope));
      });
    }
    if (widen) {
      ++extra;
      continue;
    }
    if (!regrow || attempt >= 3) {
      choose_fit_engines(spec, c, slots, fits, units);
      cfg = c;
      warn_robust(spec, slots, fits);
      return units;
    }
  }
}

}  // namespace glint
