// The sweep behind a slot's contract (contract.h): the input, parameter and approximation parts
// over every input code the comparator keeps, exhaustive up to kExactInputBits and certified by an
// enclosure beyond (contract.md, "Exhaustive, certified or estimated").
//
// A finer input is first evaluated at ~2^20 evenly spaced codes S, always with the first two kept
// codes and 1.0, and the largest parts seen there are the running bounds Bp, Ba. Where M (model),
// F (float_model) and r (the lobe) are non-decreasing (SpecularUnit::models_monotone; r always
// is), every code c between neighbours a < b of S has M(c) in [M(a), M(b)] and F(t_c), r(t_c) in
// their ranges, so
//   |M(c) - F(t_c)| <= max(M(b) - F(t_a), F(t_b) - M(a))   (and likewise for F - r).
// An interval whose enclosure, plus kEnclosureMargin, stays within the running bound holds no
// larger value; the others are bisected (codes evaluated, bounds raised), part by part, largest
// excess first, down to neighbouring codes, where nothing lies between. The parts are then the
// exact maxima over every kept code, as an exhaustive sweep would state them. Past refine_budget
// evaluations, the enclosures of the intervals left (plus the margin) join the bounds: still
// bounds, not maxima.
//
// The input part needs no refinement: a half cell's rise W(x) = r(x + h/2) - r(x) has no interior
// maximum on the codes' half cells above the first code (r' is monotone for t^n on (0, 1], and
// for Källberg's Gaussian lobe first decreasing, then increasing in t: W' = r'(x + h/2) - r'(x)
// changes sign at most once, from - to +), so its largest value over the codes between two samples
// is at one of theirs. The sample at 1.0 closes the range (the lobe is flat above 1).
#pragma once

#include <cstdint>
#include <functional>

namespace glint {

// The slot's functions: M at an input code, F and r at a real t (r at t >= -1).
struct SlotFunctions {
  std::function<double(std::int64_t)> model;
  std::function<double(double)> float_model;
  std::function<double(double)> ref;
};

struct SweptParts {
  double input = 0, parameter = 0, approximation = 0;
  // Bounds (every code, or the enclosure); false: the maxima at the sampled codes, estimates.
  bool certified = true;
  // Every interval was refined down to neighbouring codes (or every code swept): the parameter
  // and approximation parts are the exact maxima, not only bounds.
  bool tight = true;
  std::uint64_t evaluations = 0;  // codes at which M, F and r were evaluated
};

// What the doubles' rounding can move M, F and r by (a few 2^-53 of values in [0, 1], up to 2^-40
// for a high-degree polynomial's cancellation), with room to spare: far below any figure a report
// prints (2^-32 is 6e-8 of an 8-bit LSB).
inline constexpr double kEnclosureMargin = 0x1p-32;

// Evaluations beyond the ~2^20 samples the refinement may spend on one sweep (half of them at
// most on the approximation part, refined first): the sweep costs at most twice the samples'.
inline constexpr std::uint64_t kRefineBudget = std::uint64_t{1} << 20;

// The parts over the codes first..one (values code * h; code 0 stands for t in [-1, h/2]).
// Every code when there are at most sample_limit, else sample_limit evenly spaced ones, refined
// as above when `monotone` (else certified = false).
SweptParts sweep_parts(const SlotFunctions& fn, std::int64_t first, std::int64_t one, double h,
                       bool monotone, std::int64_t sample_limit,
                       std::uint64_t refine_budget = kRefineBudget);

}  // namespace glint
