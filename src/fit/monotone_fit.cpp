// The monotone fits of monotone.h: the Bernstein cone (NNLS) and constrained least squares (LSI).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/linalg.h"
#include "fit/monotone.h"
#include "fit/subspace.h"
#include "reference/reference.h"

namespace glint {

namespace {

long double binom(int n, int k) {
  long double r = 1;
  for (int i = 1; i <= k; ++i) r = r * static_cast<long double>(n - k + i) / i;
  return r;
}

// B_{k,p}(v), k = 0..p, by products (no pow: this runs for every sample of every pass).
void bernstein_basis(int p, double v, double* out) {
  double pw = 1.0;
  for (int k = 0; k <= p; ++k) {
    out[k] = pw;
    pw *= v;
  }
  double qw = 1.0;
  const double r = 1.0 - v;
  for (int k = p; k >= 0; --k) {
    out[k] *= qw * static_cast<double>(binom(p, k));
    qw *= r;
  }
}

// Solves min ||A x - y|| with x_j >= 0 for j >= free_cols (the first free_cols are unconstrained):
// Lawson & Hanson's active-set algorithm (Solving Least Squares Problems, ch. 23), the passive
// set's least squares by Householder QR.
std::vector<double> nnls(const linalg::Matrix& a, const std::vector<double>& y, std::size_t free) {
  const std::size_t n = a.cols;
  std::vector<double> x(n, 0.0);
  std::vector<bool> passive(n, false);
  for (std::size_t j = 0; j < free; ++j) passive[j] = true;
  auto solve_passive = [&] {
    std::vector<std::size_t> cols;
    for (std::size_t j = 0; j < n; ++j)
      if (passive[j]) cols.push_back(j);
    std::vector<double> s(n, 0.0);
    if (cols.empty()) return s;
    linalg::Matrix sub(a.rows, cols.size());
    for (std::size_t i = 0; i < a.rows; ++i)
      for (std::size_t k = 0; k < cols.size(); ++k) sub(i, k) = a(i, cols[k]);
    const std::vector<double> z = linalg::least_squares(sub, y);
    for (std::size_t k = 0; k < cols.size(); ++k) s[cols[k]] = z[k];
    return s;
  };
  double norm = 0;
  for (double v : a.data) norm = std::max(norm, std::abs(v));
  const double tol = 1e-12 * norm * static_cast<double>(a.rows);
  if (free > 0) x = solve_passive();
  for (int outer = 0; outer < 3 * static_cast<int>(n) + 10; ++outer) {
    std::vector<double> r = y;
    for (std::size_t i = 0; i < a.rows; ++i)
      for (std::size_t j = 0; j < n; ++j) r[i] -= a(i, j) * x[j];
    std::size_t best = n;
    double wmax = tol;
    for (std::size_t j = free; j < n; ++j) {
      if (passive[j]) continue;
      double w = 0;
      for (std::size_t i = 0; i < a.rows; ++i) w += a(i, j) * r[i];
      if (w > wmax) {
        wmax = w;
        best = j;
      }
    }
    if (best == n) break;
    passive[best] = true;
    for (int inner = 0; inner < 3 * static_cast<int>(n) + 10; ++inner) {
      const std::vector<double> s = solve_passive();
      bool feasible = true;
      double alpha = 1.0;
      for (std::size_t j = free; j < n; ++j) {
        if (passive[j] && s[j] <= 0.0) {
          feasible = false;
          alpha = std::min(alpha, x[j] / (x[j] - s[j]));
        }
      }
      if (feasible) {
        x = s;
        break;
      }
      for (std::size_t j = 0; j < n; ++j) x[j] += alpha * (s[j] - x[j]);
      for (std::size_t j = free; j < n; ++j) {
        if (passive[j] && x[j] <= 1e-15) {
          passive[j] = false;
          x[j] = 0.0;
        }
      }
    }
  }
  return x;
}

// Lawson's step towards minimax: w_i <- w_i |e_i| / sum_j w_j |e_j|. Returns the largest new weight
// (0 when every weighted error is 0, which leaves nothing to reweight: the fit is exact).
double lawson_update(std::vector<double>& w, const std::vector<double>& err) {
  double wsum = 0, wmax = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    w[i] *= err[i];
    wsum += w[i];
  }
  if (!(wsum > 0)) return 0.0;
  for (double& wi : w) wmax = std::max(wmax, wi /= wsum);
  return wmax;
}

}  // namespace

std::vector<double> fit_monotone_cone(const std::vector<double>& v, const std::vector<double>& y,
                                      const MonotoneFitOptions& o) {
  const int p = o.degree;
  if (p < 1) throw std::invalid_argument("monotone fit: degree must be >= 1");
  if (v.size() != y.size() || v.size() < static_cast<std::size_t>(p) + 1)
    throw std::invalid_argument("monotone fit: too few samples");
  if (o.zero && !o.one) throw std::invalid_argument("monotone fit: P(0) = 0 needs P(1) = 1");
  if (!(o.min_slope >= 0.0) || (o.one && o.min_slope >= 1.0))
    throw std::invalid_argument(
        fmt::format("monotone fit: slope margin {} out of range", o.min_slope));
  const double step = o.min_slope / p;
  // Columns: b_0, of either sign (absent when P(0) = 0), then d_1..d_p with basis
  // T_j(v) = sum_{k >= j} B_{k,p}(v). The target absorbs the margin: d_j = delta + d'_j.
  const std::size_t free = o.zero ? 0 : 1;
  const std::size_t cols = free + static_cast<std::size_t>(p);
  const std::size_t rows = v.size() + (o.one ? 1 : 0);
  linalg::Matrix a(rows, cols);
  std::vector<double> g(rows, 0.0);
  std::vector<double> bern(static_cast<std::size_t>(p) + 1);
  for (std::size_t i = 0; i < v.size(); ++i) {
    bernstein_basis(p, v[i], bern.data());
    double tail = 0;
    double margin = 0;
    for (int j = p; j >= 1; --j) {
      tail += bern[j];
      a(i, free + j - 1) = tail;
      margin += step * tail;
    }
    if (!o.zero) a(i, 0) = 1.0;
    g[i] = y[i] - margin;
  }
  // P(1) = b_0 + sum d_j = 1 as a heavily weighted row, made exact after the solve.
  const double total = 1.0 - step * p;
  const double heavy = 1e4 * std::sqrt(static_cast<double>(v.size()));
  if (o.one) {
    for (std::size_t j = 0; j < cols; ++j) a(rows - 1, j) = heavy;
    g[rows - 1] = heavy * total;
  }

  std::vector<double> w(v.size(), 1.0 / static_cast<double>(v.size()));
  std::vector<double> best;
  double best_err = INFINITY;
  const int passes = o.minimax ? o.lawson_passes : 1;
  for (int pass = 0; pass < passes; ++pass) {
    linalg::Matrix aw = a;
    std::vector<double> gw = g;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double s = std::sqrt(w[i] * static_cast<double>(v.size()));
      for (std::size_t j = 0; j < cols; ++j) aw(i, j) *= s;
      gw[i] *= s;
    }
    std::vector<double> x = nnls(aw, gw, free);
    double b0 = o.zero ? 0.0 : x[0];
    double sum_d = 0;
    for (int j = 0; j < p; ++j) sum_d += x[free + j];
    if (o.one) {
      if (o.zero) {
        const double scale = sum_d > 0 ? total / sum_d : 0.0;
        for (int j = 0; j < p; ++j) x[free + j] = sum_d > 0 ? x[free + j] * scale : total / p;
      } else {
        b0 = total - sum_d;
      }
    }
    std::vector<double> b(static_cast<std::size_t>(p) + 1);
    b[0] = b0;
    for (int j = 1; j <= p; ++j) b[j] = b[j - 1] + step + x[free + j - 1];
    // Errors on the samples, then Lawson's update w_i <- w_i |e_i| / sum.
    double err = 0;
    std::vector<double> e(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      bernstein_basis(p, v[i], bern.data());
      double f = 0;
      for (int k = 0; k <= p; ++k) f += b[k] * bern[k];
      e[i] = std::abs(f - y[i]);
      err = std::max(err, e[i]);
    }
    if (err < best_err) {
      best_err = err;
      best = b;
    }
    if (!(lawson_update(w, e) > 0)) break;
    for (double& wi : w) wi = std::max(wi, 1e-300);
  }
  return monomial_from_bernstein(best);
}

namespace {

// min ||E x - f|| subject to G x >= h (Lawson & Hanson ch. 23): with E = Q R, z = R x - Q'f the
// problem becomes the least-distance problem min ||z|| s.t. G R^-1 z >= h - G x0 (x0 the free
// least-squares solution), whose solution is read off the NNLS residual of [G R^-1 | ht]' u ~
// e_{m+1}. False when the constraints are infeasible or E is rank deficient.
bool lsi(const linalg::Matrix& e, const std::vector<double>& f, const linalg::Matrix& g,
         const std::vector<double>& h, std::vector<double>* x) {
  const linalg::QR qr(e);
  if (!qr.full_rank()) return false;
  const std::size_t m = e.cols, k = g.rows;
  const std::vector<double> x0 = qr.solve(f);
  linalg::Matrix lhs(m + 1, k);
  std::vector<double> row(m);
  for (std::size_t r = 0; r < k; ++r) {
    for (std::size_t j = 0; j < m; ++j) row[j] = g(r, j);
    const std::vector<double> gt = qr.rt_solve(row);  // row r of G R^-1
    double gx = 0;
    for (std::size_t j = 0; j < m; ++j) gx += g(r, j) * x0[j];
    for (std::size_t j = 0; j < m; ++j) lhs(j, r) = gt[j];
    lhs(m, r) = h[r] - gx;
  }
  std::vector<double> rhs(m + 1, 0.0);
  rhs[m] = 1.0;
  std::vector<double> u;
  try {
    u = nnls(lhs, rhs, 0);
  } catch (const std::runtime_error&) {  // a numerically dependent passive set
    return false;
  }
  std::vector<double> res(m + 1);
  for (std::size_t i = 0; i <= m; ++i) {
    double s = -rhs[i];
    for (std::size_t r = 0; r < k; ++r) s += lhs(i, r) * u[r];
    res[i] = s;
  }
  if (!(std::abs(res[m]) > 1e-12)) return false;  // ||r|| = 0: infeasible
  std::vector<double> z(m);
  for (std::size_t j = 0; j < m; ++j) z[j] = -res[j] / res[m];
  *x = qr.r_solve(z);
  for (std::size_t j = 0; j < m; ++j) (*x)[j] += x0[j];
  return true;
}

// The LSI fit with K constraint points; empty when it fails. What is asked of clamp(P, 0, 1) is
// monotonicity, and a good fit pinned to P(0) = 0 under a target of eps/c_y dips below 0 first
// (or overshoots 1 before P(1) = 1): so the points where `shape` (the previous candidate) is <= 0
// from v = 0 on are held at P <= 0, those where it is >= 1 up to v = 1 at P >= 1, and the rest at
// P' >= slope. All are linear constraints on the coefficients.
std::vector<double> fit_lsi(const std::vector<double>& v, const std::vector<double>& y,
                            const MonotoneFitOptions& o, int points, double slope,
                            const std::vector<double>& shape) {
  Subspace sub;
  sub.zero = o.zero;
  sub.one = o.one;
  sub.m = o.degree + 1 - (o.zero ? 1 : 0) - (o.one ? 1 : 0);
  if (sub.m == 0) return sub.monomial({}, o.degree);
  const std::size_t m = static_cast<std::size_t>(sub.m);
  linalg::Matrix e(v.size(), m), g(static_cast<std::size_t>(points), m);
  std::vector<double> f(v.size()), h(g.rows);
  for (std::size_t i = 0; i < v.size(); ++i) {
    sub.basis(v[i], &e.data[i * m]);
    f[i] = y[i] - sub.a(v[i]);
  }
  // Chebyshev-spaced points, both ends included: the slope of a polynomial changes fastest there.
  std::vector<double> vk(static_cast<std::size_t>(points));
  for (int k = 0; k < points; ++k)
    vk[k] = 0.5 * (1.0 - std::cos(3.14159265358979323846 * k / (points - 1)));
  int low = 0, high = points;
  if (o.min_slope <= 0 && !shape.empty()) {
    while (low < points && horner(shape, vk[low]) <= 0.0) ++low;
    while (high > low && horner(shape, vk[high - 1]) >= 1.0) --high;
  }
  for (int k = 0; k < points; ++k) {
    double* row = &g.data[static_cast<std::size_t>(k) * m];
    if (k < low) {  // -P >= 0
      sub.basis(vk[k], row);
      for (std::size_t j = 0; j < m; ++j) row[j] = -row[j];
      h[k] = sub.a(vk[k]);
    } else if (k >= high) {  // P >= 1
      sub.basis(vk[k], row);
      h[k] = 1.0 - sub.a(vk[k]);
    } else {
      sub.basis_prime(vk[k], row);
      h[k] = slope - sub.a_prime();
    }
  }
  std::vector<double> w(v.size(), 1.0), best;
  double best_err = INFINITY;
  const int passes = o.minimax ? o.lawson_passes : 1;
  for (int pass = 0; pass < passes; ++pass) {
    linalg::Matrix ew = e;
    std::vector<double> fw = f;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double s = std::sqrt(w[i]);
      for (std::size_t j = 0; j < m; ++j) ew(i, j) *= s;
      fw[i] *= s;
    }
    std::vector<double> c;
    if (!lsi(ew, fw, g, h, &c)) break;
    double err = 0;
    std::vector<double> d(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      d[i] = std::abs(sub.a(v[i]) + sub.w(v[i]) * Subspace::chebyshev(c, v[i]) - y[i]);
      err = std::max(err, d[i]);
    }
    if (err < best_err) {
      best_err = err;
      best = c;
    }
    const double wmax = lawson_update(w, d);
    if (!(wmax > 0)) break;
    // A floor keeps every sample in the design (full rank) without pulling the fit.
    for (double& wi : w) wi = std::max(wi, 1e-9 * wmax);
  }
  if (best.empty()) return {};
  return sub.monomial(best, o.degree);
}

bool proven(const std::vector<double>& c, double min_slope) {
  if (min_slope <= 0) return check_monotone(c) == Monotonicity::kProven;
  const std::vector<long double> lc(c.begin(), c.end());
  return slope_below(lc, min_slope, std::ldexp(1.0, -24)).empty();
}

}  // namespace

std::vector<double> fit_monotone(const std::vector<double>& v, const std::vector<double>& y,
                                 const MonotoneFitOptions& o, bool* cone,
                                 const std::vector<double>* start) {
  if (cone) *cone = false;
  std::vector<double> shape = start ? *start : std::vector<double>{};
  // P' >= slope holds only at the points; between them it can dip by O(spacing^2). Each retry
  // doubles the points and raises the margin tenfold (from 1e-6, a negligible constraint on P).
  double margin = 1e-6;
  int points = 8 * (o.degree + 1);
  for (int attempt = 0; attempt < 5; ++attempt, margin *= 10, points = std::min(2 * points, 256)) {
    std::vector<double> c = fit_lsi(v, y, o, points, std::max(1.5 * o.min_slope, margin), shape);
    if (c.empty()) break;
    if (o.one) {  // the monomial conversion rounds: make P(1) = 1 exact
      const std::size_t k = o.zero ? 1 : 0;
      for (int pass = 0; pass < 4; ++pass) {
        const double miss = 1.0 - horner(c, 1.0);
        if (miss == 0.0) break;
        c[k] += miss;
      }
    }
    if (proven(c, o.min_slope)) return c;
    shape = std::move(c);
  }
  if (cone) *cone = true;
  return fit_monotone_cone(v, y, o);
}

}  // namespace glint
