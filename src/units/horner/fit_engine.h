// horner's fit engines (key fit): glint's own fit (fit.h, which the datapath then rounds to
// nearest on its grid) and Sollya's fpminimax, which searches that grid itself
// (fit/sollya_fit.h), compared per slot on the same (n, tau_q, degree, widths).
//
// Measure: the error of the polynomial as the datapath holds it, P_q, against t^n on [tau_q, 1],
// two ways, both of which Sollya's fit must win for fit=best to keep it: Sollya's certified sup
// norm of P_q - t^n (its upper end below glint's lower end) and the largest |clamp(P_q, 0, 1) -
// t^n| on one dense grid of u (what the unit outputs; not above glint's). A Sollya fit is also kept
// only where the unit stays as built: monotone by the same proofs as glint's (polynomial and
// output, horner_monotone.cpp), within the guard the glint fits chose and within their coefficient
// and accumulator widths, so cost, timing and RTL shape are the glint fit's.
#pragma once

#include <vector>

#include "units/horner/slots.h"

namespace glint {

// Sollya fits this spec: method=minimax on the tau domain, with a free coefficient.
bool sollya_fits(const HornerFitSpec& spec);

// Per slot i (units[i] built at cfg from fits[i]), by spec.engine: kGlint leaves both alone;
// kBest replaces the slot by Sollya's fit where it wins (header comment); kSollya replaces every
// slot, throwing std::invalid_argument (naming the slot and the reason) where Sollya's fit is not
// valid. A slot holding Sollya's fit carries its certified sup norm (HornerCoefficients::sup_*).
//
// Cost: fpminimax 10 to 50 ms a fit, supnorm 15 to 40 ms (2-core machine, degrees 2 to 10), both
// memoized per process like fit_slot's fits. fit=best skips both where the glint fit as held is
// within 2^-11 of the lowest error any polynomial of its space can have (Remez's levelled error, or
// tau^n pinned at u = 0 by P(0) = 0): Sollya cannot win there by more than its sup norm's
// enclosure tells apart. It skips them too for a non-integer n with tau_q < 1/16, where t^n's
// branch point at t = 0 makes supnorm take seconds (fit=sollya refuses those slots).
void choose_fit_engines(const HornerFitSpec& spec, const HornerConfig& cfg,
                        const std::vector<MaterialParams>& slots,
                        std::vector<HornerCoefficients>& fits, std::vector<HornerUnit>& units);

}  // namespace glint
