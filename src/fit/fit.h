// Polynomial fits of the power lobe t^n, the coefficient source for polynomial shading units.
//
// Two domains:
//  * kFull: Öztürk §2 / eq.7. A polynomial in x = t fitted on (0, 1]; the standard clamp zeroes
//    t <= 0 (Källberg: the conventional test is the threshold tau = 0).
//  * kTau: our combination of Källberg's threshold with approximation (Källberg §3 suggests
//    exactly this pairing). The comparator already zeroes t <= tau, so the polynomial only has
//    to be right on [tau, 1]. It is expressed in u = (t - tau)/(1 - tau) in [0, 1]: the monomial
//    basis in u stays well conditioned, while monomials in t on a short interval near 1 are
//    nearly collinear. Below tau the gated unit outputs 0 where the truth is t^n <= tau^n =
//    eps/c_y, so the skipped region contributes at most tau^n (FitResult::skipped_error_bound).
//
// Methods: Öztürk's plain least squares (eq.10) and robust bisquare regression (§2.1), plus true
// minimax by the Remez exchange algorithm. All solve in a Chebyshev basis with Householder QR
// and convert to monomials only at the end.
//
// Constraints f(1) = 1 and f(lower end) = 0 are imposed exactly by fitting in a subspace:
// f(v) = a(v) + w(v) q(v), where a interpolates the constrained values and w vanishes at the
// constrained points, so every candidate satisfies them and the fit only chooses q. The "zero"
// point is the lower end of the domain: t = tau for kTau (continuity with the gated region, as in
// Hast eq.2), t = 0 for kFull (no constant offset, i.e. Öztürk's beta_0 = 0).
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace glint {

enum class FitMethod : std::uint8_t { kLeastSquares, kRobust, kMinimax };
enum class FitDomain : std::uint8_t { kFull, kTau };
// The variable the coefficients are in: kT for kFull (x = t), kU for kTau (u as above).
enum class FitVariable : std::uint8_t { kT, kU };

const char* to_string(FitMethod m);    // "ls", "robust", "minimax"
const char* to_string(FitDomain d);    // "full", "tau"
const char* to_string(FitVariable v);  // "t", "u"
// Accept "ls"/"least-squares", "robust", "minimax"; "full", "tau". Throw std::invalid_argument.
FitMethod parse_fit_method(std::string_view text);
FitDomain parse_fit_domain(std::string_view text);

// Bisquare IRLS as MATLAB robustfit does it (the tool Öztürk §3 used).
struct RobustOptions {
  double tuning = 4.685;  // Tukey's constant: 95% efficiency under Gaussian noise
  int max_iterations = 50;
  bool adjust_leverage = true;  // residuals divided by sqrt(1 - h_i)
};

struct FitOptions {
  double shininess = 20.0;  // n > 0
  int degree = 4;           // 0..kMaxFitDegree
  FitMethod method = FitMethod::kLeastSquares;
  FitDomain domain = FitDomain::kFull;
  double tau = 0.0;  // kTau only; in [0, 1)
  bool constrain_one = false;
  bool constrain_zero = false;
  // Least squares / robust: uniform samples. kFull: x_i = i/N, i = 1..N (Öztürk §3 samples the
  // open end 0 < x). kTau: u_i = i/(N-1), i = 0..N-1.
  int samples = 2000;
  RobustOptions robust{};
  int max_remez_iterations = 60;
  double remez_tolerance = 1e-9;  // relative gap between the levelled and the true max error
  // Points of Remez's search grid (Chebyshev-spaced); each extremum found on it is then refined
  // by golden-section search. 0: max(4097, 256 (m + 1)), dense enough for any domain; a smooth
  // target (t^n in u on [tau, 1]) needs far fewer.
  int remez_grid = 0;
  int error_grid = 20001;  // points of the dense grid the reported errors come from; 0: none
  // Guarantee clamp(P, 0, 1) non-decreasing in its variable on [0, 1] (monotone.h): the fit is
  // kept if check_monotone() proves it, else replaced by fit_monotone() with the same constraints
  // (ls, robust: least squares under P' >= 0; minimax: Lawson's reweighting of it).
  bool monotone = false;
  // With monotone: replace the fit by one with P' >= min_slope proven on all of [0, 1] (a margin
  // against coefficient quantization; < 1 with constrain_one).
  double min_slope = 0.0;
};

inline constexpr int kMaxFitDegree = 16;

struct FitResult {
  // Monomial coefficients in the evaluation variable, coeffs[0] the constant term (Öztürk eq.7
  // order, ready for horner()).
  std::vector<double> coeffs;
  FitVariable variable = FitVariable::kT;
  double tau = 0.0;  // lower end of the domain in t (0 for kFull)
  double shininess = 0.0;
  int degree = 0;
  FitMethod method = FitMethod::kLeastSquares;
  FitDomain domain = FitDomain::kFull;

  // Against t^n on error_grid points of the fitted domain: (0, 1] for kFull, [tau, 1] for kTau.
  double max_abs_error = 0.0;
  double rms_error = 0.0;
  double t_at_max_error = 0.0;
  // Largest error of the gated unit below tau (truth t^n, output 0): tau^n; 0 for kFull.
  double skipped_error_bound = 0.0;
  bool monotone = false;       // non-decreasing on the dense grid, up to Horner rounding
  bool monotone_fit = false;   // fit_monotone() replaced the method's own fit (see monotone)
  bool monotone_cone = false;  // ... and had to fall back to its Bernstein cone

  // Robust only: the largest |P - t^n| over the fit's own samples, of this fit and of the least-
  // squares fit with the same options (samples, constraints, monotone). t^n is noise-free, so
  // bisquare weights can reject the highlight as outliers (see fit_samples below): see
  // robust_rejects_samples().
  double sample_max_error = 0.0;
  double ls_sample_max_error = 0.0;

  int iterations = 0;     // Remez exchanges or IRLS passes; 0 for plain least squares
  bool converged = true;  // Remez/IRLS met its tolerance
  // Remez only: the levelled error |E| and the final reference, in the evaluation variable. The
  // error f - t^n alternates in sign with magnitude |E| at the reference points.
  double levelled_error = 0.0;
  std::vector<double> reference;

  double to_variable(double t) const;
  // Inverse of to_variable, exact at both ends (v = 0 gives tau, v = 1 gives 1).
  double to_t(double v) const;
  double value(double v) const;  // Horner in the evaluation variable
  double value_at_t(double t) const { return value(to_variable(t)); }
  // The unit as built: 0 where the comparator skips (t <= tau), the polynomial above.
  double gated_value_at_t(double t) const { return t <= tau ? 0.0 : value_at_t(t); }
};

// Fits t^n as configured. Throws std::invalid_argument for bad options.
FitResult fit_power(const FitOptions& options);

// Fits any function y(v) on v in [0, 1] as fit_power fits t^n on the tau domain (the pieces of a
// piecewise unit: their target normalised to y(0) = 0, y(1) = 1, so that the constraints pin both
// ends). method: least squares or minimax; `shininess` only scales Remez's rounding floor (t^n
// amplifies the rounding of t n-fold); domain and tau are not read. The result's to_variable and
// skipped_error_bound do not apply.
FitResult fit_function(const FitOptions& options, const std::function<double(double)>& y);

// A robust fit of t^n whose largest error on its samples exceeds the least-squares fit's on the
// same samples by more than that error itself (twice as large) or by more than kRobustLoss of the
// lobe's peak: its weights dropped samples the function really passes through (the highlight),
// which noise-free data never calls for. On t^n the only residual is the polynomial's own bias, so
// there is no outlier to reject; a robust fit that stays within these margins of least squares
// (n = 5: 10 to 20 % above it) only redistributes the bias, one beyond them has thrown the
// highlight away (n = 20, degree 4, full domain: 0.9996 against 0.2899).
inline constexpr double kRobustLoss = 0.1;
bool robust_rejects_samples(const FitResult& r);

// Polynomial regression on given samples (Öztürk eq.7/eq.10, §2.1), for measured data or data
// with outliers. method is kLeastSquares or kRobust (kMinimax throws: it needs the function).
// The fit runs in x mapped onto [0, 1]; the coefficients handed back are monomial in x itself, a
// form that loses digits when the data sits on a short interval far from 0 (e.g. [tau, 1]).
//
// Robust fitting assumes the residuals are noise. On noise-free t^n the residuals are the
// approximation bias instead, which concentrates where t^n is steep, and bisquare weights then
// reject exactly the highlight (see test_fit.cpp,
// RobustFit.NoiseFreeFullDomainRejectsTheHighlight). Use it for noisy samples; for the function
// itself use least squares or minimax.
struct SampleFit {
  std::vector<double> coeffs;
  std::vector<double> weights;  // final bisquare weights (all 1 for least squares)
  int iterations = 0;
  bool converged = true;
};
SampleFit fit_samples(const std::vector<double>& x, const std::vector<double>& y, int degree,
                      FitMethod method, const RobustOptions& robust = {});

}  // namespace glint
