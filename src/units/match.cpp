#include "units/match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace glint {
namespace {

// Sample points of [0, 1] for the error scan, each held as t and s = 1 - t (s exactly, so that
// (t - tau)/(1 - tau) and t^n near t = 1 keep their digits), with t^n precomputed: the grid depends
// on n only, so one grid serves every parameter the search tries.
struct PowerGrid {
  std::vector<double> t, s, tn;
};

// Geometric in s from 1e-3/n to 1 (t^n and its approximants change at the scale 1/n below t = 1),
// geometric in t from 1e-9 up (t^n with n < 1 is steep at 0), plus both ends. Consecutive points
// are at most ~10 % apart in s near 1, so every hump of the error spans several points and the
// golden-section refinement between a grid maximum's neighbours finds its top.
PowerGrid power_grid(double n) {
  constexpr int kNearOne = 160, kNearZero = 48;
  std::vector<double> s;
  s.reserve(kNearOne + kNearZero + 2);
  const double s_min = std::min(1e-3, 1e-3 / n);
  const double step = std::log(s_min) / (kNearOne - 1);
  for (int i = 0; i < kNearOne; ++i) s.push_back(std::exp(step * i));  // s_min .. 1
  for (int i = 0; i < kNearZero; ++i)
    s.push_back(1.0 - std::exp(std::log(1e-9) * (1.0 - i / double(kNearZero))));  // t 1e-9 .. ~0.65
  s.push_back(0.0);
  std::sort(s.begin(), s.end(), std::greater<>());  // increasing t
  s.erase(std::unique(s.begin(), s.end()), s.end());
  PowerGrid g;
  g.s = s;
  for (double si : s) {
    g.t.push_back(1.0 - si);
    g.tn.push_back(si >= 1.0 ? 0.0 : std::exp(n * std::log1p(-si)));
  }
  return g;
}

double pow_s(double n, double s) {
  return s >= 1.0 ? 0.0 : std::exp(n * std::log1p(-s));
}

// Golden-section search for the maximum of phi on [a, b] (phi unimodal there: the bracket is a grid
// maximum's two neighbours). 24 steps shrink the bracket by 0.618^24 ~ 1e-5: the maximum's value
// is then off by ~1e-10 of the hump's curvature times the bracket's square, far below any ulp.
template <class Phi>
double golden_max(const Phi& phi, double a, double b) {
  constexpr double kR = 0.6180339887498949;
  double c = b - kR * (b - a), d = a + kR * (b - a);
  double fc = phi(c), fd = phi(d);
  for (int i = 0; i < 24; ++i) {
    if (fc > fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - kR * (b - a);
      fc = phi(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + kR * (b - a);
      fd = phi(d);
    }
  }
  return std::max(fc, fd);
}

// Over- and undershoot of g (a function of s = 1 - t) against t^n: the grid's extremes, each
// refined between its neighbours. `kink_s` (>= 0) is a point where g has a corner (Hast's root),
// scanned as well: t^n - g rises up to it, so the undershoot's top can sit right there.
template <class G>
MatchError scan(const PowerGrid& grid, double n, const G& g, double kink_s = -1.0) {
  const std::size_t m = grid.s.size();
  double best_over = -1, best_under = -1;
  std::size_t i_over = 0, i_under = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double e = g(grid.s[i]) - grid.tn[i];
    if (e > best_over) best_over = e, i_over = i;
    if (-e > best_under) best_under = -e, i_under = i;
  }
  auto refine = [&](std::size_t i, double sign, double best) {
    // Neighbours in s (grid.s decreases with i).
    const double hi_s = grid.s[i > 0 ? i - 1 : i], lo_s = grid.s[i + 1 < m ? i + 1 : i];
    const auto phi = [&](double s) { return sign * (g(s) - pow_s(n, s)); };
    double v = golden_max(phi, lo_s, hi_s);
    if (kink_s >= lo_s && kink_s <= hi_s) v = std::max(v, phi(kink_s));
    return std::max(best, v);
  };
  MatchError e;
  e.over = std::max(0.0, refine(i_over, 1.0, best_over));
  e.under = std::max(0.0, refine(i_under, -1.0, best_under));
  if (kink_s >= 0 && kink_s <= 1) {
    // The kink's own bracket: the error between the grid points around it.
    const auto it = std::lower_bound(grid.s.begin(), grid.s.end(), kink_s, std::greater<>());
    const std::size_t j = static_cast<std::size_t>(it - grid.s.begin());
    if (j > 0 && j < m) {
      const auto phi = [&](double s) { return pow_s(n, s) - g(s); };
      e.under = std::max({e.under, phi(kink_s), golden_max(phi, grid.s[j], kink_s)});
    }
  }
  return e;
}

// Finds x in [xmin, xmax] where over(x) - under(x) changes sign (over falls, under rises with x):
// first a bracket, walking out from x0 -/+ step in doubling steps, then safeguarded regula falsi
// (Illinois). Returns the x with the smallest max(over, under) seen: an end of the range when the
// sign does not change inside it. A good seed x0 (the closed-form width match) saves the walk.
template <class Err>
double balance(const Err& err, double x0, double step, double xmin, double xmax, MatchError* out) {
  double lo = std::max(xmin, x0 - step), hi = std::min(xmax, x0 + step);
  MatchError e_lo = err(lo), e_hi = err(hi);
  double best_x = lo;
  MatchError best = e_lo;
  auto keep = [&](double x, const MatchError& e) {
    if (e.max() < best.max()) best = e, best_x = x;
  };
  keep(hi, e_hi);
  const auto h = [](const MatchError& e) { return e.over - e.under; };
  while (h(e_lo) < 0 && lo > xmin) {  // under wins at lo: the optimum lies lower
    hi = lo, e_hi = e_lo;
    step *= 2;
    lo = std::max(xmin, lo - step);
    e_lo = err(lo);
    keep(lo, e_lo);
  }
  while (h(e_hi) > 0 && hi < xmax) {  // over wins at hi: the optimum lies higher
    lo = hi, e_lo = e_hi;
    step *= 2;
    hi = std::min(xmax, hi + step);
    e_hi = err(hi);
    keep(hi, e_hi);
  }
  double h_lo = h(e_lo), h_hi = h(e_hi);
  if (h_lo <= 0) {
    best = e_lo, best_x = lo;
  } else if (h_hi >= 0) {
    best = e_hi, best_x = hi;
  } else {
    // Stops once over and under agree to 1e-12: then max(over, under) is within 1e-12 of the
    // optimum (over and under cross with slopes of opposite signs, so the max is off the optimum
    // by less than their difference).
    int side = 0;
    for (int it = 0; it < 100 && hi - lo > 1e-13 * std::max(1.0, std::fabs(lo)); ++it) {
      double x = (lo * h_hi - hi * h_lo) / (h_hi - h_lo);
      // Regula falsi inside the bracket; bisection if it leaves it or every 8th step, so that
      // a kinked P - N cannot stall it.
      if (!(x > lo && x < hi) || it % 8 == 7) x = lo + 0.5 * (hi - lo);
      const MatchError e = err(x);
      keep(x, e);
      const double h = e.over - e.under;
      if (std::fabs(h) <= 1e-12) break;
      if (h > 0) {
        lo = x, h_lo = h;
        if (side == 1) h_hi *= 0.5;  // Illinois: the same end moved twice, weight the other
        side = 1;
      } else {
        hi = x, h_hi = h;
        if (side == -1) h_lo *= 0.5;
        side = -1;
      }
    }
  }
  if (out) *out = best;
  return best_x;
}

// f = ((t - tau)/(1 - tau))^d in terms of s = 1 - t and w = 1 - tau: (w - s)/w.
double hast_of_s(double s, double w, int d) {
  if (s >= w) return 0.0;
  const double u = 1.0 - s / w;
  double p = u;
  for (int k = 1; k < d; ++k) p *= u;
  return p;
}

double schlick_of_s(double s, double n_prime) {
  const double t = 1.0 - s;
  return t <= 0 ? 0.0 : t / (n_prime * s + t);
}

MatchError hast_error_on(const PowerGrid& grid, double n, double w, int d) {
  return scan(
      grid, n, [w, d](double s) { return hast_of_s(s, w, d); }, w);
}

// The Hast search coordinate y = -log(1 - tau): tau = 0 at y = 0, 1 - tau = 1e-12 at y ~ 27.6.
constexpr double kHastYMax = 27.6;

double hast_minimax_on(const PowerGrid& grid, double n, int d, MatchError* err) {
  // Seeded at the width match's root (the minimax root lies a little below it).
  const double y0 = -std::log1p(-hast_width_root(n, d));
  const double y = balance([&](double y) { return hast_error_on(grid, n, std::exp(-y), d); }, y0,
                           0.125, 0.0, kHastYMax, err);
  return -std::expm1(-y);
}

}  // namespace

MatchMode parse_match_mode(const std::string& text) {
  if (text == "minimax") return MatchMode::kMinimax;
  if (text == "width") return MatchMode::kWidth;
  return MatchMode::kNone;
}

const char* to_string(MatchMode mode) {
  switch (mode) {
    case MatchMode::kMinimax:
      return "minimax";
    case MatchMode::kWidth:
      return "width";
    case MatchMode::kNone:
      break;
  }
  return "none";
}

double half_width_t(double n) {
  return std::exp(-std::log(2.0) / n);
}

MatchError schlick_error(double n, double n_prime) {
  return scan(power_grid(n), n, [n_prime](double s) { return schlick_of_s(s, n_prime); });
}

double schlick_width_n(double n) {
  // 1 - t_half = -expm1(-ln2/n) keeps its digits at large n.
  return half_width_t(n) / -std::expm1(-std::log(2.0) / n);
}

double schlick_minimax_n(double n, MatchError* err) {
  const PowerGrid grid = power_grid(n);
  const auto e = [&](double x) {
    const double np = std::exp(x);
    return scan(grid, n, [np](double s) { return schlick_of_s(s, np); });
  };
  // Seeded at 1.3 times the width match's n' (the minimax n' is ~1.3 times it for n >= 2).
  const double x0 = std::log(1.3 * schlick_width_n(n));
  const double x =
      balance(e, x0, 0.125, std::log(n) - std::log(1e6), std::log(n) + std::log(1e6), err);
  return std::exp(x);
}

MatchError hast_error(double n, double tau, int d) {
  return hast_error_on(power_grid(n), n, 1.0 - tau, d);
}

double hast_width_root(double n, int d) {
  // 1 - tau = (1 - t_half)/(1 - a), both differences by expm1 to keep their digits.
  const double one_minus_th = -std::expm1(-std::log(2.0) / n);
  const double one_minus_a = -std::expm1(-std::log(2.0) / d);
  return std::max(0.0, 1.0 - one_minus_th / one_minus_a);
}

double hast_minimax_root(double n, int d, MatchError* err) {
  return hast_minimax_on(power_grid(n), n, d, err);
}

HastMatch hast_minimax_joint(double n, int d_max) {
  const PowerGrid grid = power_grid(n);
  HastMatch best;
  best.error.over = best.error.under = std::numeric_limits<double>::infinity();
  const int top = static_cast<int>(std::min<double>(d_max, std::ceil(n)));
  for (int d = 1; d <= std::max(top, 1); ++d) {
    MatchError e;
    const double tau = hast_minimax_on(grid, n, d, &e);
    if (e.max() < best.error.max()) best = HastMatch{d, tau, e};
  }
  return best;
}

}  // namespace glint
