// The Bernstein form and the monotonicity check of monotone.h.
#include "fit/monotone.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace glint {

namespace {

using LVec = std::vector<long double>;

long double binom(int n, int k) {
  long double r = 1;
  for (int i = 1; i <= k; ++i) r = r * static_cast<long double>(n - k + i) / i;
  return r;
}

template <class T>
std::vector<T> to_bernstein(const std::vector<T>& c) {
  const int p = static_cast<int>(c.size()) - 1;
  std::vector<T> b(c.size(), T(0));
  for (int k = 0; k <= p; ++k) {
    long double s = 0;
    for (int j = 0; j <= k; ++j) s += binom(k, j) / binom(p, j) * static_cast<long double>(c[j]);
    b[k] = static_cast<T>(s);
  }
  return b;
}

// Bernstein coefficients of P' (degree p - 1) and a bound of their rounding error.
LVec derivative_bernstein(const LVec& c, long double* slack) {
  if (c.size() < 2) {
    *slack = 0;
    return {0.0L};
  }
  LVec a(c.size() - 1);
  long double mag = 0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    a[j] = static_cast<long double>(j + 1) * c[j + 1];
    mag += std::fabs(a[j]);
  }
  // Each coefficient is a sum of <= 10 terms with weights <= 1, each rounded a few times: 64
  // roundings of the largest possible sum is a safe margin, and subdivision only averages.
  *slack = 64 * LDBL_EPSILON * mag;
  return to_bernstein(a);
}

// de Casteljau at the midpoint.
void split(const LVec& b, LVec& left, LVec& right) {
  LVec w = b;
  const std::size_t q = b.size() - 1;
  left.resize(b.size());
  right.resize(b.size());
  left[0] = w[0];
  right[q] = w[q];
  for (std::size_t r = 1; r <= q; ++r) {
    for (std::size_t i = 0; i + r <= q; ++i) w[i] = 0.5L * (w[i] + w[i + 1]);
    left[r] = w[0];
    right[q - r] = w[q - r];
  }
}

// A piece of the subdivision: Bernstein coefficients of P and of P' on it, and its flags.
struct Leaf {
  bool rising = false;  // P' >= 0 proven
  bool low = false;     // P <= 0 proven (clamped to 0)
  bool high = false;    // P >= 1 proven (clamped to 1)
};

struct Walk {
  long double slack_p = 0, slack_d = 0;
  std::vector<Leaf> leaves;
  bool refuted = false, undecided = false;

  void visit(const LVec& bp, const LVec& bd, int depth) {
    if (refuted) return;
    Leaf f;
    f.rising = *std::min_element(bd.begin(), bd.end()) >= slack_d;
    if (f.rising) {  // P is largest at the right end and smallest at the left end
      f.low = bp.back() <= slack_p;
      f.high = bp.front() >= 1 - slack_p;
    } else {
      f.low = *std::max_element(bp.begin(), bp.end()) <= slack_p;
      f.high = *std::min_element(bp.begin(), bp.end()) >= 1 - slack_p;
    }
    if (f.rising || f.low || f.high) {
      leaves.push_back(f);
      return;
    }
    // The end coefficients are the values at the ends: P falling where 0 < P < 1 is a step back
    // of clamp(P).
    const auto inside = [&](long double v) { return v > slack_p && v < 1 - slack_p; };
    if ((bd.front() < -slack_d && inside(bp.front())) ||
        (bd.back() < -slack_d && inside(bp.back()))) {
      refuted = true;
      return;
    }
    if (depth == 0) {
      undecided = true;
      leaves.push_back(Leaf{true, false, false});
      return;
    }
    LVec pl, pr, dl, dr;
    split(bp, pl, pr);
    split(bd, dl, dr);
    visit(pl, dl, depth - 1);
    visit(pr, dr, depth - 1);
  }

  // clamp(P, 0, 1) is non-decreasing iff [0, 1] splits into a prefix where P <= 0, a middle where
  // P rises, and a suffix where P >= 1 (each possibly empty).
  Monotonicity verdict() const {
    if (refuted) return Monotonicity::kRefuted;
    std::size_t i = 0;
    while (i < leaves.size() && leaves[i].low) ++i;
    while (i < leaves.size() && leaves[i].rising) ++i;
    while (i < leaves.size() && leaves[i].high) ++i;
    if (i < leaves.size()) return Monotonicity::kRefuted;
    return undecided ? Monotonicity::kUndecided : Monotonicity::kProven;
  }
};

void below_piece(const LVec& b, long double want, double lo, double hi, double min_width,
                 std::vector<Interval>& out) {
  if (*std::min_element(b.begin(), b.end()) >= want) return;
  if (hi - lo <= min_width) {
    if (!out.empty() && out.back().hi == lo) {
      out.back().hi = hi;
    } else {
      out.push_back({lo, hi});
    }
    return;
  }
  LVec l, r;
  split(b, l, r);
  const double mid = 0.5 * (lo + hi);
  below_piece(l, want, lo, mid, min_width, out);
  below_piece(r, want, mid, hi, min_width, out);
}

}  // namespace

std::vector<double> bernstein_from_monomial(const std::vector<double>& c) {
  return to_bernstein(c);
}

std::vector<double> monomial_from_bernstein(const std::vector<double>& b) {
  const int p = static_cast<int>(b.size()) - 1;
  std::vector<double> c(b.size(), 0.0);
  for (int i = 0; i <= p; ++i) {
    long double s = 0;
    for (int k = 0; k <= i; ++k) {
      const long double t = binom(p, k) * binom(p - k, i - k) * static_cast<long double>(b[k]);
      s += (i - k) % 2 == 0 ? t : -t;
    }
    c[i] = static_cast<double>(s);
  }
  return c;
}

Monotonicity check_monotone(const std::vector<long double>& c, int max_depth) {
  Walk w;
  const LVec bd = derivative_bernstein(c, &w.slack_d);
  long double mag = 0;
  for (long double x : c) mag += std::fabs(x);
  w.slack_p = 64 * LDBL_EPSILON * mag;
  w.visit(to_bernstein(c), bd, max_depth);
  return w.verdict();
}

Monotonicity check_monotone(const std::vector<double>& c, int max_depth) {
  return check_monotone(LVec(c.begin(), c.end()), max_depth);
}

std::vector<Interval> slope_below(const std::vector<long double>& c, long double want,
                                  double min_width) {
  long double slack = 0;
  const LVec b = derivative_bernstein(c, &slack);
  std::vector<Interval> out;
  below_piece(b, want + slack, 0.0, 1.0, min_width, out);
  return out;
}

double slope_bound(const std::vector<double>& c) {
  return slope_bound(LVec(c.begin(), c.end()));
}

double slope_bound(const std::vector<long double>& c) {
  long double slack = 0;
  const LVec b = derivative_bernstein(c, &slack);
  long double m = 0;
  for (long double x : b) m = std::max(m, std::fabs(x));
  return static_cast<double>(m + slack);
}

}  // namespace glint
