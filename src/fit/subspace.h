// The constrained polynomial space of the fits (fit.cpp, monotone.cpp).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace glint {

// The fit lives in v in [0, 1] for both domains (v = x = t for kFull, v = u for kTau), in the
// constrained form f(v) = a(v) + w(v) q(v), with q = sum_j c_j T*_j(v) and T*_j(v) = T_j(2v - 1)
// the shifted Chebyshev polynomials. Chebyshev rather than monomial columns keep the least
// squares and Remez matrices near-orthogonal; w vanishes at the constrained points.
struct Subspace {
  bool zero = false;  // f(0) = 0
  bool one = false;   // f(1) = 1
  int m = 0;          // number of free coefficients c_j (degree + 1 - constraints)

  double a(double v) const { return zero && one ? v : (one ? 1.0 : 0.0); }
  double w(double v) const { return (zero ? v : 1.0) * (one ? 1.0 - v : 1.0); }

  // phi_j(v) = w(v) T*_j(v), j < m.
  void basis(double v, double* out) const {
    if (m == 0) return;
    const double s = 2.0 * v - 1.0;
    const double wv = w(v);
    double t0 = 1.0, t1 = s;
    out[0] = wv;
    for (int j = 1; j < m; ++j) {
      out[j] = wv * t1;
      const double t2 = 2.0 * s * t1 - t0;
      t0 = t1;
      t1 = t2;
    }
  }

  double a_prime() const { return zero && one ? 1.0 : 0.0; }
  double w_prime(double v) const {
    if (zero && one) return 1.0 - 2.0 * v;
    return zero ? 1.0 : (one ? -1.0 : 0.0);
  }

  // phi_j'(v) = w' T*_j + w T*_j', with T*_j'(v) = 2 j U_{j-1}(2v - 1) (Chebyshev U).
  void basis_prime(double v, double* out) const {
    if (m == 0) return;
    const double s = 2.0 * v - 1.0;
    const double wv = w(v), wp = w_prime(v);
    double t0 = 1.0, t1 = s, u0 = 0.0, u1 = 1.0;  // T_{j-1}, T_j, U_{j-2}, U_{j-1}
    out[0] = wp;
    for (int j = 1; j < m; ++j) {
      out[j] = wp * t1 + wv * 2.0 * j * u1;
      const double t2 = 2.0 * s * t1 - t0, u2 = 2.0 * s * u1 - u0;
      t0 = t1;
      t1 = t2;
      u0 = u1;
      u1 = u2;
    }
  }

  // q(v) by Clenshaw's recurrence.
  static double chebyshev(const std::vector<double>& c, double v) {
    const double s = 2.0 * v - 1.0;
    double b1 = 0.0, b2 = 0.0;
    for (std::size_t j = c.size(); j-- > 1;) {
      const double b0 = 2.0 * s * b1 - b2 + c[j];
      b2 = b1;
      b1 = b0;
    }
    return c.empty() ? 0.0 : s * b1 - b2 + c[0];
  }

  // Monomial coefficients in v of a + w q, padded to degree + 1 entries.
  std::vector<double> monomial(const std::vector<double>& c, int degree) const {
    const std::size_t len = static_cast<std::size_t>(degree) + 1;
    std::vector<double> q(len, 0.0);
    std::vector<double> prev{1.0}, cur{-1.0, 2.0};  // T*_0 = 1, T*_1 = 2v - 1
    for (std::size_t j = 0; j < c.size(); ++j) {
      const std::vector<double>& tj = j == 0 ? prev : cur;
      for (std::size_t k = 0; k < tj.size() && k < len; ++k) q[k] += c[j] * tj[k];
      if (j >= 1) {  // T*_{j+1} = 2(2v - 1) T*_j - T*_{j-1}
        std::vector<double> next(cur.size() + 1, 0.0);
        for (std::size_t k = 0; k < cur.size(); ++k) {
          next[k + 1] += 4.0 * cur[k];
          next[k] -= 2.0 * cur[k];
        }
        for (std::size_t k = 0; k < prev.size(); ++k) next[k] -= prev[k];
        prev = std::move(cur);
        cur = std::move(next);
      }
    }
    std::vector<double> wpoly{1.0};
    if (zero) wpoly = {0.0, 1.0};
    if (one) {  // multiply by (1 - v)
      std::vector<double> r(wpoly.size() + 1, 0.0);
      for (std::size_t k = 0; k < wpoly.size(); ++k) {
        r[k] += wpoly[k];
        r[k + 1] -= wpoly[k];
      }
      wpoly = r;
    }
    std::vector<double> out(len, 0.0);
    for (std::size_t i = 0; i < len; ++i) {
      for (std::size_t k = 0; k < wpoly.size() && i + k < len; ++k) out[i + k] += q[i] * wpoly[k];
    }
    if (zero && one) {
      out[1] += 1.0;
    } else if (one) {
      out[0] += 1.0;
    }
    return out;
  }
};

}  // namespace glint
