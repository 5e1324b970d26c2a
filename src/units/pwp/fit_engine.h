// pwp's fit engines (key fit), per segment: glint's (segment_fit.h: Remez with both ends exact,
// the free coefficients then rounded to nearest, datapath.h) and Sollya's fpminimax, which searches
// the coefficient grid itself with the same ends (fit/sollya_fit.h: fit_segment_fixed_point).
//
// Both hold c_0 = T_k and c_0 + ... + c_d = T_{k+1} (the rounded t^n at the segment's ends), so
// neighbours meet either way; they differ in c_2 .. c_d (and c_1, which takes the rest). Degree 1
// has no free coefficient: its segment is the chord whatever the engine.
//
// A Sollya segment is kept only where the unit stays as built: its quantized polynomial proven
// non-decreasing (pwp_nondecreasing), every coefficient within the bank widths and its sum of
// magnitudes within the accumulator the glint fits built (so cost, timing and RTL shape are
// theirs), and the output non-decreasing over the segment's codes and its neighbours' at the guard
// the glint fits chose. fit=best keeps it only where, besides, Sollya's certified sup norm of
// |P_k,q - t^n| on the segment lies wholly below glint's (upper end below lower end) and its
// largest error over the segment's input codes is lower (over 2^10 + 1 points of x where the
// segment has more codes); fit=sollya wherever its sup norm is certified.
//
// Cost: fpminimax, given its interpolation points (the interior extrema of glint's real fit's
// error), takes about 0.1 ms a segment, supnorm 2 to 10 ms (this 2-core machine), both memoized
// per process. fit=best spends them only where Sollya could win by more than a sixteenth of the
// coefficients' LSB (2^-(cf+4)), on at most 4 segments a datapath group, those where it could win
// the most:
// - every segment with the ends T_k, T_{k+1} errs by at least their rounding, floor = max(|T_k
//   2^-cf - a^n|, |T_{k+1} 2^-cf - b^n|), and by at least the real minimax fit's error (exact
//   ends, glint's Remez) less floor: glint's segment within 2^-(cf+4) of the larger is kept;
// - the error over the segment's codes is convex in the free coefficients, so at degree 2 a walk
//   from glint's c_2 finds the grid's best: where it gains less than 2^-(cf+4), so would Sollya.
//   At degree 3 the eight neighbours of glint's (c_2, c_3) stand in for the lattice (a heuristic).
// Segments whose start is below 1/16 for a non-integer n keep glint's fit under either engine:
// t^n's branch point at t = 0 makes supnorm take seconds (as horner's fit_engine.h).
#pragma once

#include <string_view>
#include <vector>

#include "units/pwp/datapath.h"

namespace glint {

enum class PwpFitEngine : std::uint8_t { kBest, kGlint, kSollya };
PwpFitEngine parse_pwp_fit_engine(std::string_view text);

// units: one per datapath group, built by glint's fits, guard chosen (pwp.cpp). Replaces segments
// by Sollya's fits as the engine says and records the choice in each unit (fit_record()).
void choose_pwp_fit_engines(PwpFitEngine engine, std::vector<PwpUnit>& units);

}  // namespace glint
