#include "eval/contract_sweep.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace glint {
namespace {

struct Values {
  double m = 0, f = 0, r = 0;
};

enum class Part { kParameter, kApproximation };

class Sweep {
 public:
  Sweep(const SlotFunctions& fn, double h) : fn_(fn), h_(h) {}

  // M, F and r at a code, folded into the parameter and approximation parts.
  Values at(std::int64_t code) {
    ++out_.evaluations;
    const double t = static_cast<double>(code) * h_;
    const Values v{fn_.model(code), fn_.float_model(t), fn_.ref(t)};
    out_.parameter = std::max(out_.parameter, std::fabs(v.m - v.f));
    out_.approximation = std::max(out_.approximation, std::fabs(v.f - v.r));
    return v;
  }
  // Both halves of the code's rounding cell; code 0's reaches down to t = -1.
  void fold_input(std::int64_t code, double r) {
    const double t = static_cast<double>(code) * h_;
    const double bottom = code == 0 ? fn_.ref(-1.0) : fn_.ref(t - 0.5 * h_);
    out_.input = std::max({out_.input, r - bottom, fn_.ref(t + 0.5 * h_) - r});
  }

  // The enclosure of a part over the codes strictly between a and b (monotone M, F and r), with
  // the rounding margin, and by how much it exceeds the part's running bound.
  static double enclosure(Part part, const Values& a, const Values& b) {
    return (part == Part::kParameter ? std::max(b.m - a.f, b.f - a.m)
                                     : std::max(b.f - a.r, b.r - a.f)) +
           kEnclosureMargin;
  }
  double excess(Part part, const Values& a, const Values& b) const {
    return enclosure(part, a, b) - bound(part);
  }

  // Bisects [a, b] until every piece's enclosure is within the part's running bound or the piece
  // has no code inside; past the budget, a piece's enclosure joins the part's pending bound.
  void refine(Part part, std::int64_t a, const Values& va, std::int64_t b, const Values& vb,
              std::uint64_t budget_end) {
    stack_.assign(1, {a, b, va, vb});
    while (!stack_.empty()) {
      const Piece p = stack_.back();
      stack_.pop_back();
      if (p.b - p.a <= 1 || excess(part, p.va, p.vb) <= 0) continue;
      if (out_.evaluations >= budget_end) {
        double& pending = part == Part::kParameter ? pending_parameter_ : pending_approximation_;
        pending = std::max(pending, enclosure(part, p.va, p.vb));
        out_.tight = false;
        continue;
      }
      const std::int64_t mid = p.a + (p.b - p.a) / 2;
      const Values vm = at(mid);
      stack_.push_back({mid, p.b, vm, p.vb});
      stack_.push_back({p.a, mid, p.va, vm});
    }
  }

  SweptParts finish() {
    out_.parameter = std::max(out_.parameter, pending_parameter_);
    out_.approximation = std::max(out_.approximation, pending_approximation_);
    return out_;
  }
  SweptParts& out() { return out_; }
  double bound(Part part) const {
    return part == Part::kParameter ? out_.parameter : out_.approximation;
  }

 private:
  struct Piece {
    std::int64_t a, b;
    Values va, vb;
  };

  const SlotFunctions& fn_;
  double h_;
  SweptParts out_;
  std::vector<Piece> stack_;  // refine's pieces still to look at
  double pending_parameter_ = 0, pending_approximation_ = 0;
};

}  // namespace

SweptParts sweep_parts(const SlotFunctions& fn, std::int64_t first, std::int64_t one, double h,
                       bool monotone, std::int64_t sample_limit, std::uint64_t refine_budget) {
  Sweep sweep(fn, h);
  const std::int64_t count = one - first + 1;
  if (count <= sample_limit) {
    // Every code: each cell's upper half edge is the next one's lower edge.
    double lower_edge = first == 0 ? fn.ref(-1.0) : fn.ref((static_cast<double>(first) - 0.5) * h);
    for (std::int64_t code = first; code <= one; ++code) {
      const double t = static_cast<double>(code) * h;
      const Values v = sweep.at(code);
      const double upper_edge = fn.ref(t + 0.5 * h);
      sweep.out().input = std::max({sweep.out().input, v.r - lower_edge, upper_edge - v.r});
      lower_edge = upper_edge;
    }
    return sweep.finish();
  }

  // Evenly spaced codes, with the first two (the input part's argument starts above code 0's
  // cell, contract_sweep.h) and 1.0: code_at(0) = first, code_at(1) = first + 1, then first +
  // (i - 1) step below 1.0, and 1.0 last.
  const std::int64_t step = (count + sample_limit - 1) / sample_limit;
  const std::size_t samples = static_cast<std::size_t>((one - 1 - first) / step) + 3;
  const auto code_at = [&](std::size_t i) -> std::int64_t {
    if (i < 2) return first + static_cast<std::int64_t>(i);
    return i + 1 == samples ? one : first + static_cast<std::int64_t>(i - 1) * step;
  };
  std::vector<Values> values;
  values.reserve(samples);
  for (std::size_t i = 0; i < samples; ++i) {
    values.push_back(sweep.at(code_at(i)));
    sweep.fold_input(code_at(i), values.back().r);
  }
  if (!monotone) {
    sweep.out().certified = false;
    sweep.out().tight = false;
    return sweep.finish();
  }

  // Part by part, the intervals whose enclosure exceeds the running bound are refined, largest
  // excess first (by its binary exponent: a counting sort, where a full sort of 2^20 intervals
  // cost as much as their refinement): they raise the bound soonest, which settles most others
  // without an evaluation, and past the budget the enclosures left are the smallest. The
  // approximation part first, with half the budget: its largest values sit at a few extrema of
  // F - r, found in few evaluations, where the parameter part (M and F nearly equal) may need
  // every code and should not starve it.
  const std::uint64_t sampled_evaluations = sweep.out().evaluations;
  // Bucket b holds excesses in [2^(b - 63), 2^(b - 62)) (values lie in [0, 1]); smaller ones in 0.
  constexpr int kBuckets = 64;
  std::vector<int> bucket_of(samples - 1);
  std::vector<std::uint32_t> order(samples - 1);
  for (const Part part : {Part::kApproximation, Part::kParameter}) {
    const std::uint64_t budget_end =
        sampled_evaluations + (part == Part::kApproximation ? refine_budget / 2 : refine_budget);
    std::vector<std::uint32_t> next(kBuckets, 0);  // counts, then each bucket's next place
    for (std::size_t i = 0; i + 1 < samples; ++i) {
      const double e = sweep.excess(part, values[i], values[i + 1]);
      int& b = bucket_of[i];
      b = !(e > 0) || code_at(i + 1) - code_at(i) <= 1
              ? -1
              : kBuckets - 1 - std::clamp(-std::ilogb(e), 0, kBuckets - 1);
      if (b >= 0) ++next[static_cast<std::size_t>(b)];
    }
    std::uint32_t total = 0;
    for (int b = kBuckets - 1; b >= 0; --b) {  // the largest bucket first
      const std::uint32_t n = next[static_cast<std::size_t>(b)];
      next[static_cast<std::size_t>(b)] = total;
      total += n;
    }
    for (std::size_t i = 0; i + 1 < samples; ++i)
      if (bucket_of[i] >= 0)
        order[next[static_cast<std::size_t>(bucket_of[i])]++] = static_cast<std::uint32_t>(i);
    for (std::uint32_t k = 0; k < total; ++k) {
      const std::size_t i = order[k];
      sweep.refine(part, code_at(i), values[i], code_at(i + 1), values[i + 1], budget_end);
    }
  }
  return sweep.finish();
}

}  // namespace glint
