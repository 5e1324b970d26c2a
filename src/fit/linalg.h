// Small dense least squares for the polynomial fits: Householder QR, never normal equations.
// Forming A'A squares the condition number, which for a degree-10 basis on [0, 1] is the
// difference between a usable fit and noise. Sizes here are a few thousand rows by <= 20 columns.
#pragma once

#include <cstddef>
#include <vector>

namespace glint::linalg {

// Dense row-major matrix.
struct Matrix {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> data;

  Matrix() = default;
  Matrix(std::size_t r, std::size_t c) : rows(r), cols(c), data(r * c, 0.0) {}
  double& operator()(std::size_t r, std::size_t c) { return data[r * cols + c]; }
  double operator()(std::size_t r, std::size_t c) const { return data[r * cols + c]; }
};

// Householder QR factorisation A = QR of a rows >= cols matrix, reflectors kept in place.
class QR {
 public:
  explicit QR(const Matrix& a);

  // False when some |R_jj| <= 1e-13 * max |R_jj| (numerically rank deficient).
  bool full_rank() const { return full_rank_; }
  // argmin ||A x - b||_2. Throws std::runtime_error if the matrix is rank deficient.
  std::vector<double> solve(const std::vector<double>& b) const;
  // R^-1 z and R^-T g for the triangular factor (n-vectors): the pieces of Lawson & Hanson's
  // reduction of inequality-constrained least squares to a least-distance problem.
  std::vector<double> r_solve(std::vector<double> z) const;
  std::vector<double> rt_solve(std::vector<double> g) const;
  // Diagonal of the hat matrix A (A'A)^-1 A' = squared row norms of the thin Q (the leverages).
  std::vector<double> leverages() const;

 private:
  void apply_qt(std::vector<double>& b) const;  // b <- Q' b

  // Column-major copy of A: every loop of the factorisation and of Q'b runs down a column, so
  // each is a contiguous, vectorisable sweep (Matrix is row-major for the callers that fill rows).
  double at(std::size_t r, std::size_t c) const { return qr_[c * rows_ + r]; }
  const double* column(std::size_t c) const { return &qr_[c * rows_]; }
  double* column(std::size_t c) { return &qr_[c * rows_]; }

  std::size_t rows_ = 0;
  std::size_t cols_ = 0;
  std::vector<double> qr_;    // R on and above the diagonal, reflector tails below it
  std::vector<double> beta_;  // reflector scale: H_j = I - beta_j v_j v_j', v_j(j) = 1
  std::vector<double> diag_;  // R_jj
  bool full_rank_ = true;
};

// Convenience: argmin ||A x - b||_2.
std::vector<double> least_squares(const Matrix& a, const std::vector<double>& b);

}  // namespace glint::linalg
