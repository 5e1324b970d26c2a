// Parameters of Schlick's and Hast's formulas that best match t^n for a given n, for fair
// comparisons against the units that approximate t^n itself (pow, lut, horner).
//
// The papers use their parameters differently: Schlick 1994 puts the Phong exponent straight into
// S_n(t) = t / (n - n t + t) (n' = n), whose highlight "frontiers are broader" than t^n's; Hast et
// al. 2003 pick the root tau and the order d of f(rho) = kappa (rho - tau)^d (eq.2) by eye
// ("the purpose is not really to mimic the ordinary specular computation"). Two ways of choosing
// them against t^n instead:
//
//  - minimax: the parameter minimizing E = max over t in [0, 1] of |g(t) - t^n|, the uniform error
//    every other unit is judged by. Both families are monotone in their parameter at every t
//    (S_n'(t) falls as n' grows; ((t - tau)/(1 - tau))^d falls as tau grows), so the overshoot
//    P = max (g - t^n)+ falls and the undershoot N = max (t^n - g)+ rises with the parameter: E =
//    max(P, N) is quasi-convex and its minimum is where P = N (equioscillation), or at an end of
//    the range. A bracketed root search on P - N finds it (safeguarded regula falsi, in log n' for
//    Schlick and in -log(1 - tau) for Hast, where the answers for large n crowd towards 1).
//    P and N come from a grid dense near t = 1 (features at the scale 1/n) and near t = 0 (n < 1),
//    refined by golden-section search around the grid's extremes.
//  - width: the highlight's half-width matched: g(t_half) = ½ where t_half^n = ½, i.e. the angle
//    where the highlight falls to half its peak. Closed forms below.
#pragma once

#include <string>
#include <string_view>

namespace glint {

// The `match` key of schlick and hast: none (the paper's own use), minimax or width.
enum class MatchMode { kNone, kMinimax, kWidth };
MatchMode parse_match_mode(const std::string& text);  // "minimax", "width", else none
const char* to_string(MatchMode mode);
// The key's values (schlick's and hast's keys.h).
inline constexpr std::string_view kMatchModeNames[] = {"none", "minimax", "width"};

// Largest overshoot and undershoot of an approximant against t^n over [0, 1].
struct MatchError {
  double over = 0.0;   // max (g(t) - t^n), >= 0
  double under = 0.0;  // max (t^n - g(t)), >= 0
  double max() const { return over > under ? over : under; }
};

// t_half = 2^(-1/n): where t^n = ½.
double half_width_t(double n);

// Schlick S_n'(t) = t / (n' - n' t + t) against t^n.
MatchError schlick_error(double n, double n_prime);
// n' with S_n'(t_half) = ½: n' (1 - t_half) = t_half, so n' = t_half / (1 - t_half) (~ n / ln 2
// for large n).
double schlick_width_n(double n);
// n' minimizing max |S_n' - t^n| (see above); *err (if given) receives its error.
double schlick_minimax_n(double n, MatchError* err = nullptr);

// Hast ((t - tau)/(1 - tau))^d (0 for t <= tau) against t^n; tau in [0, 1).
MatchError hast_error(double n, double tau, int d);
// tau with f(t_half) = ½: t_half - tau = 2^(-1/d) (1 - tau), so tau = (t_half - a)/(1 - a) with
// a = 2^(-1/d), clamped at 0 (n <= d: even tau = 0 gives t^d <= t^n, a highlight no wider).
double hast_width_root(double n, int d);
// tau in [0, 1) minimizing max |f - t^n| for this d; *err receives its error.
double hast_minimax_root(double n, int d, MatchError* err = nullptr);

struct HastMatch {
  int d = 1;
  double tau = 0.0;
  MatchError error;
};
// d in 1..d_max and tau jointly by minimax: the d whose minimax tau gives the smallest error (the
// smaller d on a tie: fewer multipliers). d >= n needs no search: tau = 0 is then optimal (t^d <=
// t^n everywhere) and the error grows with d, so only d <= ceil(n) are tried.
HastMatch hast_minimax_joint(double n, int d_max = 16);

}  // namespace glint
