#include "fit/linalg.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace glint::linalg {

QR::QR(const Matrix& a)
    : rows_(a.rows), cols_(a.cols), qr_(a.rows * a.cols), beta_(a.cols, 0.0), diag_(a.cols, 0.0) {
  const std::size_t m = rows_;
  const std::size_t n = cols_;
  if (m < n) throw std::invalid_argument("QR: needs at least as many rows as columns");
  for (std::size_t r = 0; r < m; ++r) {
    for (std::size_t c = 0; c < n; ++c) qr_[c * m + r] = a(r, c);
  }
  for (std::size_t j = 0; j < n; ++j) {
    double* vj = column(j);
    // Scale first: the column norm of a badly scaled column must not overflow or underflow.
    double scale = 0.0;
    for (std::size_t i = j; i < m; ++i) scale = std::max(scale, std::abs(vj[i]));
    if (scale == 0.0) {
      beta_[j] = 0.0;
      diag_[j] = 0.0;
      continue;
    }
    double norm2 = 0.0;
    for (std::size_t i = j; i < m; ++i) {
      const double s = vj[i] / scale;
      norm2 += s * s;
    }
    const double x0 = vj[j];
    // Reflect onto -sign(x0)*||x|| so that v0 = x0 - alpha involves no cancellation.
    const double alpha = (x0 >= 0.0 ? -1.0 : 1.0) * scale * std::sqrt(norm2);
    const double v0 = x0 - alpha;
    double vtv = 1.0;
    for (std::size_t i = j + 1; i < m; ++i) {
      vj[i] /= v0;
      vtv += vj[i] * vj[i];
    }
    beta_[j] = 2.0 / vtv;
    diag_[j] = alpha;
    vj[j] = alpha;
    for (std::size_t k = j + 1; k < n; ++k) {
      double* vk = column(k);
      double s = vk[j];
      for (std::size_t i = j + 1; i < m; ++i) s += vj[i] * vk[i];
      s *= beta_[j];
      vk[j] -= s;
      for (std::size_t i = j + 1; i < m; ++i) vk[i] -= s * vj[i];
    }
  }
  double dmax = 0.0;
  for (double d : diag_) dmax = std::max(dmax, std::abs(d));
  for (double d : diag_) {
    if (!(std::abs(d) > 1e-13 * dmax)) full_rank_ = false;
  }
}

void QR::apply_qt(std::vector<double>& b) const {
  const std::size_t m = rows_;
  for (std::size_t j = 0; j < cols_; ++j) {
    if (beta_[j] == 0.0) continue;
    const double* vj = column(j);
    double s = b[j];
    for (std::size_t i = j + 1; i < m; ++i) s += vj[i] * b[i];
    s *= beta_[j];
    b[j] -= s;
    for (std::size_t i = j + 1; i < m; ++i) b[i] -= s * vj[i];
  }
}

std::vector<double> QR::solve(const std::vector<double>& b) const {
  if (b.size() != rows_) throw std::invalid_argument("QR::solve: right-hand side size mismatch");
  if (!full_rank_) throw std::runtime_error("QR::solve: matrix is numerically rank deficient");
  std::vector<double> y = b;
  apply_qt(y);
  const std::size_t n = cols_;
  std::vector<double> x(n, 0.0);
  for (std::size_t j = n; j-- > 0;) {
    double s = y[j];
    for (std::size_t k = j + 1; k < n; ++k) s -= at(j, k) * x[k];
    x[j] = s / diag_[j];
  }
  return x;
}

std::vector<double> QR::r_solve(std::vector<double> z) const {
  const std::size_t n = cols_;
  if (z.size() != n) throw std::invalid_argument("QR::r_solve: size mismatch");
  for (std::size_t j = n; j-- > 0;) {
    for (std::size_t k = j + 1; k < n; ++k) z[j] -= at(j, k) * z[k];
    z[j] /= diag_[j];
  }
  return z;
}

std::vector<double> QR::rt_solve(std::vector<double> g) const {
  const std::size_t n = cols_;
  if (g.size() != n) throw std::invalid_argument("QR::rt_solve: size mismatch");
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < j; ++k) g[j] -= at(k, j) * g[k];
    g[j] /= diag_[j];
  }
  return g;
}

std::vector<double> QR::leverages() const {
  const std::size_t m = rows_;
  const std::size_t n = cols_;
  // Thin Q = H_0 ... H_{n-1} [I; 0], built column by column.
  std::vector<double> h(m, 0.0);
  std::vector<double> col(m);
  for (std::size_t c = 0; c < n; ++c) {
    std::fill(col.begin(), col.end(), 0.0);
    col[c] = 1.0;
    for (std::size_t j = std::min(c, n - 1) + 1; j-- > 0;) {
      if (beta_[j] == 0.0) continue;
      const double* vj = column(j);
      double s = col[j];
      for (std::size_t i = j + 1; i < m; ++i) s += vj[i] * col[i];
      s *= beta_[j];
      col[j] -= s;
      for (std::size_t i = j + 1; i < m; ++i) col[i] -= s * vj[i];
    }
    for (std::size_t i = 0; i < m; ++i) h[i] += col[i] * col[i];
  }
  return h;
}

std::vector<double> least_squares(const Matrix& a, const std::vector<double>& b) {
  return QR(a).solve(b);
}

}  // namespace glint::linalg
