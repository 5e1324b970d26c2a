#include "fit/fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

#include "fit/linalg.h"
#include "fit/monotone.h"
#include "fit/subspace.h"
#include "reference/reference.h"

namespace glint {

namespace {

constexpr double kPi = 3.14159265358979323846;

// t^n seen from v, with t = t0 + (1 - t0) v. The two-sided formula makes both ends exact
// (v = 0 gives t0, v = 1 gives 1), so f(1) = 1 constraints see a target of exactly 1.
double t_from_v(double t0, double v) {
  const double h = 1.0 - t0;
  return v <= 0.5 ? t0 + h * v : 1.0 - h * (1.0 - v);
}

// t^n on [t0, 1] seen from v, or (fit_function) any function of v; n then only scales Remez's
// rounding floor.
struct Target {
  double t0 = 0.0;
  double n = 1.0;
  const std::function<double(double)>* fn = nullptr;
  double t(double v) const { return t_from_v(t0, v); }
  double y(double v) const { return fn != nullptr ? (*fn)(v) : glossy_scalar(t(v), n); }
};

struct CoeffFit {
  std::vector<double> c;
  std::vector<double> weights;
  int iterations = 0;
  bool converged = true;
};

linalg::Matrix design(const Subspace& sub, const std::vector<double>& v) {
  linalg::Matrix a(v.size(), static_cast<std::size_t>(sub.m));
  for (std::size_t i = 0; i < v.size(); ++i) sub.basis(v[i], &a.data[i * a.cols]);
  return a;
}

std::vector<double> weighted_solve(const linalg::Matrix& x, const std::vector<double>& g,
                                   const std::vector<double>& weights, bool* ok) {
  linalg::Matrix a = x;
  std::vector<double> b = g;
  for (std::size_t i = 0; i < a.rows; ++i) {
    const double s = std::sqrt(weights[i]);
    for (std::size_t j = 0; j < a.cols; ++j) a(i, j) *= s;
    b[i] *= s;
  }
  linalg::QR qr(std::move(a));
  *ok = qr.full_rank();
  return *ok ? qr.solve(b) : std::vector<double>{};
}

// Öztürk eq.10: ordinary least squares, through QR on the Chebyshev design.
CoeffFit least_squares_fit(const Subspace& sub, const std::vector<double>& v,
                           const std::vector<double>& g) {
  CoeffFit out;
  out.weights.assign(v.size(), 1.0);
  if (sub.m == 0) return out;
  out.c = linalg::least_squares(design(sub, v), g);
  return out;
}

// MATLAB's madsigma: median of the |r| with the p - 1 smallest dropped, over 0.6745 (the MAD of a
// unit normal), so that s estimates the noise sigma even when some residuals are outliers.
double mad_sigma(const std::vector<double>& r, int p) {
  std::vector<double> a(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) a[i] = std::abs(r[i]);
  std::sort(a.begin(), a.end());
  const std::size_t start = std::min(a.size() - 1, static_cast<std::size_t>(std::max(1, p) - 1));
  const std::size_t cnt = a.size() - start;
  const double med =
      cnt % 2 == 1 ? a[start + cnt / 2] : 0.5 * (a[start + cnt / 2 - 1] + a[start + cnt / 2]);
  return med / 0.6745;
}

// Öztürk §2.1: bisquare-weighted iteratively reweighted least squares, following MATLAB
// robustfit (Öztürk §3 used it): leverage-adjusted residuals, MAD scale, Tukey bisquare, stop
// when every coefficient moves by less than sqrt(DBL_EPSILON) relative.
CoeffFit robust_fit(const Subspace& sub, const std::vector<double>& v, const std::vector<double>& g,
                    const RobustOptions& opt) {
  if (!(opt.tuning > 0.0)) throw std::invalid_argument("robust fit: tuning constant must be > 0");
  CoeffFit out;
  out.weights.assign(v.size(), 1.0);
  if (sub.m == 0) return out;
  const linalg::Matrix x = design(sub, v);
  const linalg::QR qr0(x);
  if (!qr0.full_rank()) throw std::runtime_error("robust fit: design matrix is rank deficient");
  std::vector<double> adj(v.size(), 1.0);
  if (opt.adjust_leverage) {
    // High-leverage points pull the fit towards themselves, which shrinks their residuals;
    // dividing by sqrt(1 - h) undoes that before the residuals are judged.
    const std::vector<double> h = qr0.leverages();
    for (std::size_t i = 0; i < v.size(); ++i) {
      adj[i] = 1.0 / std::sqrt(1.0 - std::min(h[i], 0.9999));
    }
  }
  std::vector<double> b = qr0.solve(g);
  // MATLAB's floor on the scale, 1e-6 std(y): data that lies exactly on a polynomial has
  // rounding-noise residuals, and without a floor those would be judged against each other.
  double mean = 0.0, var = 0.0;
  for (double gi : g) mean += gi;
  mean /= static_cast<double>(g.size());
  for (double gi : g) var += (gi - mean) * (gi - mean);
  double tiny_s = g.size() > 1 ? 1e-6 * std::sqrt(var / static_cast<double>(g.size() - 1)) : 0.0;
  if (tiny_s == 0.0) tiny_s = 1.0;
  std::vector<double> r(v.size());
  out.converged = false;
  for (int it = 1; it <= opt.max_iterations; ++it) {
    out.iterations = it;
    for (std::size_t i = 0; i < v.size(); ++i) {
      double fi = 0.0;
      for (std::size_t j = 0; j < x.cols; ++j) fi += x(i, j) * b[j];
      r[i] = (g[i] - fi) * adj[i];
    }
    const double s = std::max(mad_sigma(r, sub.m), tiny_s);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double u = r[i] / (opt.tuning * s);
      out.weights[i] = std::abs(u) < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
    bool ok = false;
    std::vector<double> nb = weighted_solve(x, g, out.weights, &ok);
    if (!ok) break;  // too many points rejected to determine the polynomial: keep the last fit
    bool small = true;
    const double d = std::sqrt(DBL_EPSILON);
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (std::abs(nb[j] - b[j]) > d * std::max(std::abs(nb[j]), std::abs(b[j]))) small = false;
    }
    b = std::move(nb);
    if (small) {
      out.converged = true;
      break;
    }
  }
  out.c = std::move(b);
  return out;
}

// ---- Remez exchange ---------------------------------------------------------------------------

struct Extremum {
  double v;
  double e;
};

struct RemezOut {
  std::vector<double> c;
  double levelled = 0.0;
  std::vector<double> reference;
  int iterations = 0;
  bool converged = false;
};

// Best approximation of g = t^n - a in span{w T*_j}: the error g - w q equioscillates at m + 1
// points (Chebyshev alternation; w T*_j is a Haar system wherever w != 0). Multi-point exchange:
// each pass solves the levelled-error system on the reference, takes the extremum of every
// sign-run of the error on a fine Chebyshev-spaced grid, polishes it by golden-section search,
// and keeps m + 1 consecutive alternating extrema around the global maximum.
RemezOut remez(const Subspace& sub, const Target& target, int max_iterations, double rtol,
               int grid_points) {
  RemezOut out;
  const int m = sub.m;
  auto g_at = [&](double v) { return target.y(v) - sub.a(v); };
  // Candidate grid, clustered at the ends where polynomial error extrema crowd (and where the
  // steep part of t^n sits).
  const int grid =
      grid_points > 0 ? std::max(grid_points, 4 * (m + 2)) : std::max(4097, 256 * (m + 1));
  std::vector<double> gv, gg;
  gv.reserve(grid);
  gg.reserve(grid);
  double gscale = 0.0;
  for (int i = 0; i < grid; ++i) {
    const double v = i == grid - 1 ? 1.0 : 0.5 * (1.0 - std::cos(kPi * i / (grid - 1)));
    const double g = g_at(v);
    gscale = std::max(gscale, std::abs(g));
    // A constrained point with zero error is fixed at zero and can never be an extremum.
    if (sub.w(v) == 0.0 && g == 0.0) continue;
    gv.push_back(v);
    gg.push_back(g);
  }
  if (m == 0) {  // nothing free: f = a
    for (std::size_t i = 0; i < gv.size(); ++i) {
      out.levelled = std::max(out.levelled, std::abs(gg[i]));
    }
    out.converged = true;
    return out;
  }
  const std::size_t ng = gv.size();
  std::vector<double> phi(ng * m);
  for (std::size_t i = 0; i < ng; ++i) sub.basis(gv[i], &phi[i * m]);

  // Initial reference: Chebyshev extrema, leaving out the ends pinned by constraints (w = 0).
  std::vector<double> ref;
  {
    const int lo = sub.zero ? 1 : 0;
    const int hi = sub.one ? 1 : 0;
    const int total = m + 1 + lo + hi;
    for (int k = lo; k < total - hi; ++k) {
      ref.push_back(0.5 * (1.0 - std::cos(kPi * k / (total - 1))));
    }
  }

  // Below this the gap is rounding noise: t carries a relative error of ~DBL_EPSILON and t^n
  // amplifies it n-fold, so for large n the target itself is only good to ~n ulps.
  const double abs_floor = 16.0 * DBL_EPSILON * (1.0 + target.n) * std::max(gscale, 1e-300);
  double best_gap = INFINITY;
  std::vector<double> c(m);
  std::vector<double> e(ng);
  for (int it = 1; it <= max_iterations; ++it) {
    linalg::Matrix a(m + 1, m + 1);
    std::vector<double> rhs(m + 1);
    for (int k = 0; k <= m; ++k) {
      sub.basis(ref[k], &a.data[k * (m + 1)]);
      a(k, m) = k % 2 == 0 ? 1.0 : -1.0;
      rhs[k] = g_at(ref[k]);
    }
    linalg::QR qr(std::move(a));
    if (!qr.full_rank()) break;
    const std::vector<double> sol = qr.solve(rhs);
    std::copy(sol.begin(), sol.begin() + m, c.begin());
    const double levelled = std::abs(sol[m]);

    auto err = [&](double v) { return g_at(v) - sub.w(v) * Subspace::chebyshev(c, v); };
    for (std::size_t i = 0; i < ng; ++i) {
      double f = 0.0;
      for (int j = 0; j < m; ++j) f += phi[i * m + j] * c[j];
      e[i] = gg[i] - f;
    }
    // One extremum per sign-run, polished between its grid neighbours.
    std::vector<Extremum> ext;
    std::size_t i = 0;
    while (i < ng) {
      const bool pos = e[i] >= 0.0;
      std::size_t best = i;
      std::size_t j = i;
      for (; j < ng && (e[j] >= 0.0) == pos; ++j) {
        if (std::abs(e[j]) > std::abs(e[best])) best = j;
      }
      const double sgn = pos ? 1.0 : -1.0;
      double lo = gv[best > 0 ? best - 1 : best];
      double hi = gv[best + 1 < ng ? best + 1 : best];
      Extremum x{gv[best], e[best]};
      const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = hi - gr * (hi - lo), x2 = lo + gr * (hi - lo);
      double f1 = sgn * err(x1), f2 = sgn * err(x2);
      // Stop at a millionth of the bracket: the error is flat at its extremum, so the value is
      // then good to ~1e-12 relative, far inside the exchange's tolerance.
      const double stop = std::max(1e-15, 1e-6 * (hi - lo));
      for (int k = 0; k < 100 && hi - lo > stop; ++k) {
        if (f1 > f2) {
          hi = x2;
          x2 = x1;
          f2 = f1;
          x1 = hi - gr * (hi - lo);
          f1 = sgn * err(x1);
        } else {
          lo = x1;
          x1 = x2;
          f1 = f2;
          x2 = lo + gr * (hi - lo);
          f2 = sgn * err(x2);
        }
      }
      if (f1 > sgn * x.e) x = {x1, sgn * f1};
      if (f2 > sgn * x.e) x = {x2, sgn * f2};
      ext.push_back(x);
      i = j;
    }
    std::size_t gi = 0;
    for (std::size_t k = 1; k < ext.size(); ++k) {
      if (std::abs(ext[k].e) > std::abs(ext[gi].e)) gi = k;
    }
    const double maxerr = std::abs(ext[gi].e);
    const double gap = maxerr - levelled;
    out.iterations = it;
    if (gap < best_gap) {
      best_gap = gap;
      out.c = c;
      out.levelled = levelled;
      out.reference = ref;
    }
    // Levelled and true maximum error agree: the reference is the alternation set. The absolute
    // floor covers fits that are exact up to rounding (t^n with integer n <= degree).
    if (gap <= rtol * maxerr || gap <= abs_floor) {
      out.converged = true;
      break;
    }
    const std::size_t need = static_cast<std::size_t>(m) + 1;
    if (ext.size() >= need) {
      // Of the windows of m + 1 consecutive extrema that contain the global maximum, keep the one
      // whose smallest extremum is largest: it raises the levelled error the most.
      const std::size_t s_lo = gi >= need - 1 ? gi - (need - 1) : 0;
      const std::size_t s_hi = std::min(gi, ext.size() - need);
      std::size_t s_best = s_lo;
      double s_val = -1.0;
      for (std::size_t s = s_lo; s <= s_hi; ++s) {
        double mn = INFINITY;
        for (std::size_t k = s; k < s + need; ++k) mn = std::min(mn, std::abs(ext[k].e));
        if (mn > s_val) {
          s_val = mn;
          s_best = s;
        }
      }
      for (std::size_t k = 0; k < need; ++k) ref[k] = ext[s_best + k].v;
    } else {
      // Too few sign changes (rare, early passes only): single-point exchange of the global
      // maximum into the old reference, keeping the signs alternating.
      const Extremum z = ext[gi];
      const bool zpos = z.e >= 0.0;
      auto pos_at = [&](std::size_t k) { return err(ref[k]) >= 0.0; };
      if (z.v < ref.front()) {
        if (pos_at(0) == zpos) {
          ref.front() = z.v;
        } else {
          ref.pop_back();
          ref.insert(ref.begin(), z.v);
        }
      } else if (z.v > ref.back()) {
        if (pos_at(need - 1) == zpos) {
          ref.back() = z.v;
        } else {
          ref.erase(ref.begin());
          ref.push_back(z.v);
        }
      } else {
        std::size_t k = 0;
        while (k + 1 < need && ref[k + 1] < z.v) ++k;
        if (pos_at(k) == zpos) {
          ref[k] = z.v;
        } else {
          ref[std::min(k + 1, need - 1)] = z.v;
        }
      }
    }
  }
  return out;
}

void check_options(const FitOptions& o) {
  if (!(o.shininess > 0.0) || !std::isfinite(o.shininess)) {
    throw std::invalid_argument(
        fmt::format("fit: shininess must be finite and > 0, got {}", o.shininess));
  }
  if (o.degree < 0 || o.degree > kMaxFitDegree) {
    throw std::invalid_argument(
        fmt::format("fit: degree must be in 0..{}, got {}", kMaxFitDegree, o.degree));
  }
  const int k = (o.constrain_one ? 1 : 0) + (o.constrain_zero ? 1 : 0);
  if (o.degree + 1 < k) {
    throw std::invalid_argument(
        fmt::format("fit: degree {} cannot meet {} constraints", o.degree, k));
  }
  if (o.domain == FitDomain::kTau && !(o.tau >= 0.0 && o.tau < 1.0)) {
    throw std::invalid_argument(fmt::format("fit: tau must be in [0, 1), got {}", o.tau));
  }
  if (o.method != FitMethod::kMinimax && o.samples < std::max(2, o.degree + 1)) {
    throw std::invalid_argument(fmt::format(
        "fit: {} samples cannot determine a degree-{} polynomial", o.samples, o.degree));
  }
  if (o.error_grid < 0 || o.error_grid == 1)
    throw std::invalid_argument("fit: error_grid must be 0 (none) or >= 2");
  if (o.remez_grid < 0) throw std::invalid_argument("fit: remez_grid must be >= 0");
  if (o.monotone && o.degree < 1)
    throw std::invalid_argument("fit: a monotone fit needs degree >= 1");
  if (!(o.min_slope >= 0.0) || (o.constrain_one && o.min_slope >= 1.0))
    throw std::invalid_argument(fmt::format("fit: min_slope {} is out of range", o.min_slope));
  if (o.method == FitMethod::kMinimax && o.max_remez_iterations < 1) {
    throw std::invalid_argument("fit: max_remez_iterations must be >= 1");
  }
}

void measure(FitResult& r, const Target& target, int grid) {
  const bool full = r.domain == FitDomain::kFull;
  double max_err = -1.0, sum2 = 0.0, t_max = 0.0, prev = -INFINITY;
  bool monotone = true;
  // Horner on |v| <= 1 is good to about eps * sum|coeffs|; smaller dips are rounding, not shape.
  double coeff_sum = 0.0;
  for (double c : r.coeffs) coeff_sum += std::abs(c);
  const double slack = 8.0 * DBL_EPSILON * coeff_sum;
  // kFull: t_j = j/G, j = 1..G, the half-open (0, 1]. kTau: u_j = j/(G-1), the closed [0, 1].
  for (int j = full ? 1 : 0; j < grid + (full ? 1 : 0); ++j) {
    const double v = full ? static_cast<double>(j) / grid : static_cast<double>(j) / (grid - 1);
    const double t = target.t(v);
    const double f = r.value(v);
    const double d = std::abs(f - target.y(v));
    sum2 += d * d;
    if (d > max_err) {
      max_err = d;
      t_max = t;
    }
    if (f < prev - slack) monotone = false;
    prev = f;
  }
  r.max_abs_error = max_err;
  r.rms_error = std::sqrt(sum2 / grid);
  r.t_at_max_error = t_max;
  r.monotone = monotone;
}

// With f(1) = 1: the Chebyshev-to-monomial conversion rounds, and in t on (0, 1] the monomial
// coefficients of a degree-10 fit run into the thousands, so sum(coeffs) can miss 1 by ~1e-10.
// Fold the residual into the lowest coefficient the other constraint leaves free, so that Horner
// at v = 1 (a plain sum) gives exactly 1; f(0) = coeffs[0] = 0 is already exact.
void fold_one(std::vector<double>& coeffs, const Subspace& sub) {
  if (!sub.one) return;
  const std::size_t k = sub.zero ? 1 : 0;
  for (int pass = 0; pass < 4; ++pass) {
    const double miss = 1.0 - horner(coeffs, 1.0);
    if (miss == 0.0) break;
    coeffs[k] += miss;
  }
}

// The monotone replacement fit (monotone.h) on the method's own samples: least squares and
// robust on the uniform samples (robust weights would reject the highlight on noise-free t^n, see
// fit.h, so both are plain least squares in the cone), minimax by Lawson's reweighting on a
// Chebyshev-spaced set, dense where the error of a polynomial peaks.
std::vector<double> monotone_fit(const FitOptions& o, const Subspace& sub, const Target& target,
                                 const std::vector<double>& start, bool* cone) {
  std::vector<double> v, y;
  if (o.method == FitMethod::kMinimax) {
    const int count = std::max(128, 24 * (o.degree + 1));
    for (int i = 0; i < count; ++i) v.push_back(0.5 * (1.0 - std::cos(kPi * i / (count - 1))));
  } else {
    for (int i = 0; i < o.samples; ++i) {
      v.push_back(o.domain == FitDomain::kFull ? static_cast<double>(i + 1) / o.samples
                                               : static_cast<double>(i) / (o.samples - 1));
    }
  }
  for (double vi : v) y.push_back(target.y(vi));
  MonotoneFitOptions m;
  m.degree = o.degree;
  m.zero = sub.zero;
  m.one = sub.one;
  m.minimax = o.method == FitMethod::kMinimax;
  m.min_slope = o.min_slope;
  return fit_monotone(v, y, m, cone, &start);
}

}  // namespace

const char* to_string(FitMethod m) {
  switch (m) {
    case FitMethod::kLeastSquares:
      return "ls";
    case FitMethod::kRobust:
      return "robust";
    case FitMethod::kMinimax:
      return "minimax";
  }
  return "?";
}

const char* to_string(FitDomain d) {
  return d == FitDomain::kFull ? "full" : "tau";
}
const char* to_string(FitVariable v) {
  return v == FitVariable::kT ? "t" : "u";
}

FitMethod parse_fit_method(std::string_view text) {
  if (text == "ls" || text == "least-squares") return FitMethod::kLeastSquares;
  if (text == "robust") return FitMethod::kRobust;
  if (text == "minimax") return FitMethod::kMinimax;
  throw std::invalid_argument("unknown fit method '" + std::string(text) +
                              "': expected ls, robust or minimax");
}

FitDomain parse_fit_domain(std::string_view text) {
  if (text == "full") return FitDomain::kFull;
  if (text == "tau") return FitDomain::kTau;
  throw std::invalid_argument("unknown fit domain '" + std::string(text) +
                              "': expected full or tau");
}

double FitResult::to_variable(double t) const {
  return variable == FitVariable::kT ? t : (t - tau) / (1.0 - tau);
}

double FitResult::to_t(double v) const {
  return variable == FitVariable::kT ? v : t_from_v(tau, v);
}

double FitResult::value(double v) const {
  return horner(coeffs, v);
}

namespace {

// The largest |P(v_i) - t^n| over the samples least squares and robust fit (fit_power's v_i).
double sample_max_error(const std::vector<double>& coeffs, const FitOptions& o,
                        const Target& target) {
  double worst = 0.0;
  for (int i = 0; i < o.samples; ++i) {
    const double v = o.domain == FitDomain::kFull ? static_cast<double>(i + 1) / o.samples
                                                  : static_cast<double>(i) / (o.samples - 1);
    worst = std::max(worst, std::fabs(horner(coeffs, v) - target.y(v)));
  }
  return worst;
}

}  // namespace

namespace {

FitResult fit_target(const FitOptions& o, const Target& target) {
  Subspace sub;
  sub.zero = o.constrain_zero;
  sub.one = o.constrain_one;
  sub.m = o.degree + 1 - (sub.zero ? 1 : 0) - (sub.one ? 1 : 0);

  FitResult r;
  r.variable = o.domain == FitDomain::kTau ? FitVariable::kU : FitVariable::kT;
  r.tau = target.t0;
  r.shininess = o.shininess;
  r.degree = o.degree;
  r.method = o.method;
  r.domain = o.domain;
  r.skipped_error_bound = o.domain == FitDomain::kTau ? glossy_scalar(o.tau, o.shininess) : 0.0;

  std::vector<double> c;
  if (o.method == FitMethod::kMinimax) {
    RemezOut rz = remez(sub, target, o.max_remez_iterations, o.remez_tolerance, o.remez_grid);
    c = std::move(rz.c);
    r.iterations = rz.iterations;
    r.converged = rz.converged;
    r.levelled_error = rz.levelled;
    r.reference = std::move(rz.reference);
  } else {
    std::vector<double> v(static_cast<std::size_t>(o.samples));
    std::vector<double> g(v.size());
    for (int i = 0; i < o.samples; ++i) {
      v[i] = o.domain == FitDomain::kFull ? static_cast<double>(i + 1) / o.samples
                                          : static_cast<double>(i) / (o.samples - 1);
      g[i] = target.y(v[i]) - sub.a(v[i]);
    }
    CoeffFit cf = o.method == FitMethod::kRobust ? robust_fit(sub, v, g, o.robust)
                                                 : least_squares_fit(sub, v, g);
    c = std::move(cf.c);
    r.iterations = cf.iterations;
    r.converged = cf.converged;
  }
  r.coeffs = sub.monomial(c, o.degree);
  fold_one(r.coeffs, sub);
  if (o.monotone && (o.min_slope > 0.0 || check_monotone(r.coeffs) != Monotonicity::kProven)) {
    r.coeffs = monotone_fit(o, sub, target, r.coeffs, &r.monotone_cone);
    fold_one(r.coeffs, sub);
    r.monotone_fit = true;
    r.levelled_error = 0.0;
    r.reference.clear();
  }
  if (o.error_grid > 0) measure(r, target, o.error_grid);
  if (o.method == FitMethod::kRobust) {
    FitOptions ls = o;
    ls.method = FitMethod::kLeastSquares;
    ls.error_grid = 0;
    const FitResult reference = fit_power(ls);
    r.sample_max_error = sample_max_error(r.coeffs, o, target);
    r.ls_sample_max_error = sample_max_error(reference.coeffs, o, target);
  }
  return r;
}

}  // namespace

FitResult fit_power(const FitOptions& o) {
  check_options(o);
  Target target;
  target.n = o.shininess;
  target.t0 = o.domain == FitDomain::kTau ? o.tau : 0.0;
  return fit_target(o, target);
}

FitResult fit_function(const FitOptions& o, const std::function<double(double)>& y) {
  check_options(o);
  if (o.method == FitMethod::kRobust)
    throw std::invalid_argument("fit: fit_function takes least squares or minimax");
  FitOptions opt = o;
  opt.domain = FitDomain::kTau;  // v in [0, 1], both ends in the domain
  opt.tau = 0.0;
  Target target;
  target.n = o.shininess;
  target.fn = &y;
  FitResult r = fit_target(opt, target);
  r.skipped_error_bound = 0.0;
  return r;
}

bool robust_rejects_samples(const FitResult& r) {
  // 1e-12: on data a polynomial fits exactly both errors are rounding noise.
  const double ls = r.ls_sample_max_error;
  return r.method == FitMethod::kRobust &&
         r.sample_max_error - ls > std::min(ls, kRobustLoss) + 1e-12;
}

SampleFit fit_samples(const std::vector<double>& x, const std::vector<double>& y, int degree,
                      FitMethod method, const RobustOptions& robust) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_samples: x and y sizes differ");
  if (degree < 0 || degree > kMaxFitDegree) {
    throw std::invalid_argument(
        fmt::format("fit_samples: degree must be in 0..{}, got {}", kMaxFitDegree, degree));
  }
  if (x.size() < static_cast<std::size_t>(degree) + 1) {
    throw std::invalid_argument("fit_samples: fewer samples than coefficients");
  }
  if (method == FitMethod::kMinimax) {
    throw std::invalid_argument("fit_samples: minimax needs a function, not samples");
  }
  const auto [mn, mx] = std::minmax_element(x.begin(), x.end());
  const double lo = *mn;
  const double span = *mx - *mn;
  if (!(span > 0.0) && degree > 0) {
    throw std::invalid_argument("fit_samples: all x are equal");
  }
  // Fit in v = (x - lo)/span in [0, 1], where the Chebyshev columns are well conditioned.
  std::vector<double> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = span > 0.0 ? (x[i] - lo) / span : 0.0;
  Subspace sub;
  sub.m = degree + 1;
  CoeffFit cf =
      method == FitMethod::kRobust ? robust_fit(sub, v, y, robust) : least_squares_fit(sub, v, y);
  const std::vector<double> bv = sub.monomial(cf.c, degree);
  // Substitute v = alpha x + beta by Horner's scheme on polynomials.
  const double alpha = span > 0.0 ? 1.0 / span : 0.0;
  const double beta = span > 0.0 ? -lo / span : 0.0;
  std::vector<double> p{bv.back()};
  for (std::size_t k = bv.size() - 1; k-- > 0;) {
    std::vector<double> np(p.size() + 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      np[i] += beta * p[i];
      np[i + 1] += alpha * p[i];
    }
    np[0] += bv[k];
    p = std::move(np);
  }
  p.resize(bv.size());
  SampleFit out;
  out.coeffs = std::move(p);
  out.weights = std::move(cf.weights);
  out.iterations = cf.iterations;
  out.converged = cf.converged;
  return out;
}

}  // namespace glint
