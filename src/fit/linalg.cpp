#include "fit/linalg.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace glint::linalg {

QR::QR(Matrix a) : qr_(std::move(a)), beta_(qr_.cols, 0.0), diag_(qr_.cols, 0.0) {
  const std::size_t m = qr_.rows;
  const std::size_t n = qr_.cols;
  if (m < n) throw std::invalid_argument("QR: needs at least as many rows as columns");
  for (std::size_t j = 0; j < n; ++j) {
    // Scale first: the column norm of a badly scaled column must not overflow or underflow.
    double scale = 0.0;
    for (std::size_t i = j; i < m; ++i) scale = std::max(scale, std::abs(qr_(i, j)));
    if (scale == 0.0) {
      beta_[j] = 0.0;
      diag_[j] = 0.0;
      continue;
    }
    double norm2 = 0.0;
    for (std::size_t i = j; i < m; ++i) {
      const double s = qr_(i, j) / scale;
      norm2 += s * s;
    }
    const double x0 = qr_(j, j);
    // Reflect onto -sign(x0)*||x|| so that v0 = x0 - alpha involves no cancellation.
    const double alpha = (x0 >= 0.0 ? -1.0 : 1.0) * scale * std::sqrt(norm2);
    const double v0 = x0 - alpha;
    double vtv = 1.0;
    for (std::size_t i = j + 1; i < m; ++i) {
      qr_(i, j) /= v0;
      vtv += qr_(i, j) * qr_(i, j);
    }
    beta_[j] = 2.0 / vtv;
    diag_[j] = alpha;
    qr_(j, j) = alpha;
    for (std::size_t k = j + 1; k < n; ++k) {
      double s = qr_(j, k);
      for (std::size_t i = j + 1; i < m; ++i) s += qr_(i, j) * qr_(i, k);
      s *= beta_[j];
      qr_(j, k) -= s;
      for (std::size_t i = j + 1; i < m; ++i) qr_(i, k) -= s * qr_(i, j);
    }
  }
  double dmax = 0.0;
  for (double d : diag_) dmax = std::max(dmax, std::abs(d));
  for (double d : diag_) {
    if (!(std::abs(d) > 1e-13 * dmax)) full_rank_ = false;
  }
}

void QR::apply_qt(std::vector<double>& b) const {
  const std::size_t m = qr_.rows;
  for (std::size_t j = 0; j < qr_.cols; ++j) {
    if (beta_[j] == 0.0) continue;
    double s = b[j];
    for (std::size_t i = j + 1; i < m; ++i) s += qr_(i, j) * b[i];
    s *= beta_[j];
    b[j] -= s;
    for (std::size_t i = j + 1; i < m; ++i) b[i] -= s * qr_(i, j);
  }
}

std::vector<double> QR::solve(const std::vector<double>& b) const {
  if (b.size() != qr_.rows) throw std::invalid_argument("QR::solve: right-hand side size mismatch");
  if (!full_rank_) throw std::runtime_error("QR::solve: matrix is numerically rank deficient");
  std::vector<double> y = b;
  apply_qt(y);
  const std::size_t n = qr_.cols;
  std::vector<double> x(n, 0.0);
  for (std::size_t j = n; j-- > 0;) {
    double s = y[j];
    for (std::size_t k = j + 1; k < n; ++k) s -= qr_(j, k) * x[k];
    x[j] = s / diag_[j];
  }
  return x;
}

std::vector<double> QR::r_solve(std::vector<double> z) const {
  const std::size_t n = qr_.cols;
  if (z.size() != n) throw std::invalid_argument("QR::r_solve: size mismatch");
  for (std::size_t j = n; j-- > 0;) {
    for (std::size_t k = j + 1; k < n; ++k) z[j] -= qr_(j, k) * z[k];
    z[j] /= diag_[j];
  }
  return z;
}

std::vector<double> QR::rt_solve(std::vector<double> g) const {
  const std::size_t n = qr_.cols;
  if (g.size() != n) throw std::invalid_argument("QR::rt_solve: size mismatch");
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < j; ++k) g[j] -= qr_(k, j) * g[k];
    g[j] /= diag_[j];
  }
  return g;
}

std::vector<double> QR::leverages() const {
  const std::size_t m = qr_.rows;
  const std::size_t n = qr_.cols;
  // Thin Q = H_0 ... H_{n-1} [I; 0], built column by column.
  std::vector<double> h(m, 0.0);
  std::vector<double> col(m);
  for (std::size_t c = 0; c < n; ++c) {
    std::fill(col.begin(), col.end(), 0.0);
    col[c] = 1.0;
    for (std::size_t j = std::min(c, n - 1) + 1; j-- > 0;) {
      if (beta_[j] == 0.0) continue;
      double s = col[j];
      for (std::size_t i = j + 1; i < m; ++i) s += qr_(i, j) * col[i];
      s *= beta_[j];
      col[j] -= s;
      for (std::size_t i = j + 1; i < m; ++i) col[i] -= s * qr_(i, j);
    }
    for (std::size_t i = 0; i < m; ++i) h[i] += col[i] * col[i];
  }
  return h;
}

std::vector<double> least_squares(const Matrix& a, const std::vector<double>& b) {
  return QR(a).solve(b);
}

}  // namespace glint::linalg
