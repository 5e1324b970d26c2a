// LaneAccumulator: one lane's accuracy statistics, a row at a time (add) or a run of rows at a
// time (accumulate on any thread, merge in stream order), with the same bits either way.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "eval/deferral.h"
#include "eval/evaluate.h"

namespace glint {
namespace {

// The memo holds the facts of every (slot, code) a slot's comparator keeps for inputs up to
// kMemoMaxWidth bits, up to kMemoMaxCodes codes over all slots (evaluate.h): beyond it every
// request computes its own (a file with thousands of materials must not allocate per slot what a
// short stream never revisits).
constexpr std::int64_t kUnset = std::numeric_limits<std::int64_t>::min();

// round(clamp(v, 0, 1) * scale) as std::lround rounds (half away from zero), inline: lround is
// a library call, and the engine asks for two display codes per row. With lround, sim_speed
// with every request computed took 20 % more CPU time and glint eval 4 % (tests/bench/RESULTS.md,
// "Issue 30").
inline long display_code(double v, double scale) {
  const double y = std::clamp(v, 0.0, 1.0) * scale;
  const long k = static_cast<long>(y);  // y >= 0: truncation is floor, and y - k is exact
  return k + static_cast<long>(y - static_cast<double>(k) >= 0.5);
}

// Largest value, first row to reach it: strict >, so an equal value later keeps the first.
inline void max_at(LanePartial::MaxAt& m, double value, double t) {
  const bool more = value > m.value;
  m.value = more ? value : m.value;
  m.t = more ? t : m.t;
}

// c ? a : b on the bits: GCC turns the plain form into a branch, which costs a misprediction on
// every other row when c follows the stream's t. With the plain form sim_speed took 8 % more CPU
// time with every request computed and 4 % with 94 % skipped, for 1 % fewer instructions
// (medians of 7 alternating runs; tests/bench/RESULTS.md, "Issue 30").
inline double select(bool c, double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(c);
  const std::uint64_t bits = (x & mask) | (y & ~mask);
  double out = 0;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

// std::min(v, 1.0) for v >= 0, without a branch.
inline double min1(double v) {
  return select(v > 1.0, 1.0, v);
}

// A row's pixel error (reference/pixel_error.h) from its slot's channel weights w and their largest
// w_max: the linear encoding inline (|err| w_max, the engine's common case), sRGB per channel.
inline double row_pixel_error(bool linear, const Rgb& w, double w_max, double fixed, double ref) {
  return linear ? std::fabs(fixed - ref) * w_max
                : request_pixel_error(DisplayEncoding::kSrgb8, w, fixed, ref);
}

// The same for a skipped row (result 0): sRGB is increasing, so its largest channel is w_max's.
inline double skipped_pixel_error(bool linear, double w_max, double ref) {
  return linear ? ref * w_max : encode(DisplayEncoding::kSrgb8, ref * w_max);
}

// A largest value (strict >: the first row to reach it) with that row's index in the run, so
// that the maxima of two passes over disjoint rows join into the one of a single pass.
struct FirstMax {
  double value = -1;  // below every value: no row yet (LanePartial's total and weighted)
  double t = 0;
  std::size_t row = ~std::size_t{0};
  void add(double v, double at, std::size_t k) {
    const bool more = v > value;
    value = more ? v : value;
    t = more ? at : t;
    row = more ? k : row;
  }
  static LanePartial::MaxAt join(const FirstMax& a, const FirstMax& b) {
    const bool second = b.value > a.value || (b.value == a.value && b.row < a.row);
    return second ? LanePartial::MaxAt{b.value, b.t} : LanePartial::MaxAt{a.value, a.t};
  }
};

inline void merge_part(PartStats& s, const LanePartial::MaxAt& m) {
  if (m.value > s.max_abs) {
    s.max_abs = m.value;
    s.t_at_max = m.t;
  }
}

// ErrorStats' first row sets its maximum whatever its value (ErrorStats::add).
inline void merge_error(ErrorStats& s, const LanePartial::MaxAt& m, std::uint64_t count) {
  if (m.value >= 0 && (s.count == 0 || m.value > s.max_abs)) {
    s.max_abs = m.value;
    s.t_at_max = m.t;
  }
  s.count += count;
}

inline std::uint64_t fold_digest(std::uint64_t digest, std::uint64_t word) {
  // FNV-1a style over the whole result word (skip flag in bit 63), with a shift-xor so every bit
  // of the word reaches every bit of the digest.
  digest = (digest ^ word) * 0x100000001b3ULL;
  return digest ^ (digest >> 29);
}

inline std::uint64_t digest_word(std::int64_t out_raw, bool skipped) {
  return static_cast<std::uint64_t>(out_raw) ^ (std::uint64_t{skipped} << 63);
}

// The sequential folds, in stream order: floating-point sums and the digest do not reassociate.
// Rows in no scalar statistic add +0, which leaves the sum as it is.
inline void fold_row(double& sum, std::uint64_t& digest, double square, std::uint64_t word) {
  sum += square;
  digest = fold_digest(digest, word);
}

// The first pass of a lane's run (Run::classify) over the rows row_at(0 .. n - 1) of the run
// (consecutive rows, or those of a list): each row's input code and comparator, the computed rows
// listed with their codes and the skipped ones apart (no branch between the two: a stream takes it
// at random), every row's digest word that of a skipped row (a computed row's is written later).
// In a function of its own, every pointer a parameter: in the big function, GCC kept several on
// the stack and reloaded them on every row.
struct ClassifiedRows {
  std::size_t computed = 0, skipped = 0;
};

template <class RowAt>
ClassifiedRows classify_rows(const InputQuantizer& quantize, const double* __restrict t,
                             const std::uint32_t* __restrict slot,
                             const std::int64_t* __restrict tau, RowAt row_at, std::size_t n,
                             std::uint32_t* __restrict computed, std::int64_t* __restrict code,
                             std::uint32_t* __restrict skipped_rows,
                             std::uint64_t* __restrict word) {
  std::size_t computed_count = 0, skipped_count = 0;
  const std::uint64_t skipped_word = digest_word(0, true);
  for (std::size_t x = 0; x < n; ++x) {
    const std::uint32_t k = row_at(x);
    const std::int64_t t_raw = quantize(t[k]);
    const bool sk = t_raw <= tau[slot[k]];
    computed[computed_count] = k;
    code[computed_count] = t_raw;
    computed_count += !sk;
    skipped_rows[skipped_count] = k;
    skipped_count += sk;
    word[k] = skipped_word;
  }
  return {computed_count, skipped_count};
}

// The rows of [k0, k1) above their slot's drop_t into `out`; returns how many.
std::size_t list_rows(const double* __restrict t, const std::uint32_t* __restrict slot,
                      const double* __restrict drop_t, std::size_t k0, std::size_t k1,
                      std::uint32_t* __restrict out) {
  std::size_t n = 0;
  for (std::size_t k = k0; k < k1; ++k) {
    out[n] = static_cast<std::uint32_t>(k);
    n += t[k] > drop_t[slot[k]];
  }
  return n;
}

}  // namespace

// Per slot, the codes its comparator keeps ([first, first + size)); an entry is filled once,
// by whichever thread needs it first: the fields, then `out` with release, which readers load
// with acquire (a race between two fillers writes the same values). What every computed row reads
// is kept apart from the parts, which a row reads only while its code is not yet folded, so the
// rows' working set stays small.
struct LaneAccumulator::Memo {
  struct Hot {
    std::atomic<std::int64_t> out{kUnset};
    std::atomic<double> r{0};
  };
  struct Parts {
    std::atomic<double> approximation{0}, parameter{0}, datapath{0};
  };
  struct Table {
    std::int64_t first = 0;
    std::size_t size = 0;
    std::unique_ptr<Hot[]> hot;
    std::unique_ptr<Parts[]> parts;
    // Codes whose parts are in the statistics: a later visit cannot change a largest part or
    // the first row that reached it. Set by merge, which may run beside the next window's rows:
    // a row that misses a bit set meanwhile folds its code's parts once more, which changes
    // nothing (the same values, at a later row).
    std::unique_ptr<std::atomic<std::uint64_t>[]> folded;
    bool is_folded(std::size_t c) const {
      return (folded[c >> 6].load(std::memory_order_relaxed) >> (c & 63)) & 1;
    }
    void set_folded(std::size_t c) {
      folded[c >> 6].fetch_or(std::uint64_t{1} << (c & 63), std::memory_order_relaxed);
    }
  };
  std::vector<Table> tables;

  static CodeFacts fill(const Table& table, std::size_t c, const CodeFacts& f) {
    Parts& p = table.parts[c];
    p.approximation.store(f.approximation, std::memory_order_relaxed);
    p.parameter.store(f.parameter, std::memory_order_relaxed);
    p.datapath.store(f.datapath, std::memory_order_relaxed);
    table.hot[c].r.store(f.r, std::memory_order_relaxed);
    table.hot[c].out.store(f.out, std::memory_order_release);
    return f;
  }
};

LaneAccumulator::LaneAccumulator(const SpecularUnit& unit, const SlotMap& slots, int display_bits)
    : unit_(unit), slots_(slots) {
  stats_.name = unit.name();
  stats_.spec = unit.canonical_spec();
  stats_.display_bits = display_bits;
  ulp_ = unit.out_format().ulp();
  stats_.out_ulp = ulp_;
  in_ulp_ = unit.in_format().ulp();
  display_ = display_scale(display_bits);
  slot_state_.assign(unit.slots(), -1);
  tau_.resize(unit.slots());
  for (std::size_t s = 0; s < tau_.size(); ++s) tau_[s] = unit.tau_raw(s);
  // A deferred reference r <= 2^e reaches the pixel as at most slope * w_max * r (the encoding's
  // slope bounds it: encoding_slope): the factor SettledRows::weighted compares against.
  const double slope = encoding_slope(slots.display);
  for (const double w : slots.pixel_weight_max) {
    settle_weight_.push_back(slope * w);
    max_weight_ = std::max(max_weight_, slope * w);
  }
  set_drop_t(kDeferredExponent);
  const int width = unit.in_format().width();
  if (width <= kMemoMaxWidth && unit.slots() << width <= kMemoMaxCodes) {
    memo_ = std::make_unique<Memo>();
    memo_->tables.resize(unit.slots());
  }
}

LaneAccumulator::LaneAccumulator(LaneAccumulator&&) noexcept = default;
LaneAccumulator::~LaneAccumulator() = default;

void LaneAccumulator::begin_slot(std::size_t slot) {
  if (slot_state_[slot] >= 0) return;
  const auto [it, fresh] = contract_of_.emplace(contract_key(slot), stats_.slots.size());
  if (fresh) {
    stats_.slots.push_back(slot_contract(unit_, slot, slots_));
  } else {
    SlotContract c = stats_.slots[it->second];  // the same sweep: only who it is differs
    c.slot = slot;
    c.name = slots_.params[slot].name;
    c.weight = slots_.pixel_weight_max[slot];
    stats_.slots.push_back(std::move(c));
  }
  slot_state_[slot] = stats_.slots.back().always_skipped ? 1 : 0;
  any_always_ = any_always_ || slot_state_[slot] == 1;
  if (memo_) {
    Memo::Table& table = memo_->tables[slot];
    table.first = std::max<std::int64_t>(tau_[slot] + 1, 0);
    const std::int64_t one = unit_.in_format().raw_one();
    if (one >= table.first) {
      table.size = static_cast<std::size_t>(one - table.first + 1);
      table.hot.reset(new Memo::Hot[table.size]);
      table.parts.reset(new Memo::Parts[table.size]);
      const std::size_t words = (table.size + 63) / 64;
      table.folded.reset(new std::atomic<std::uint64_t>[words]);
      for (std::size_t w = 0; w < words; ++w) table.folded[w].store(0, std::memory_order_relaxed);
    }
  }
}

bool LaneAccumulator::computes_at_or_below(std::size_t slot, double t) const {
  // Quantization is monotone: the rows at or below t have codes at or below t's.
  return tau_[slot] < InputQuantizer(unit_.in_format())(t);
}

double LaneAccumulator::skips_at_or_below(std::size_t slot) const {
  // Quantizing is monotone, and tau's own value quantizes to tau.
  return tau_[slot] < 0 ? -std::numeric_limits<double>::infinity()
                        : static_cast<double>(tau_[slot]) * in_ulp_;
}

// At or below min(deferred_t(e), the value of tau's code) a power lobe's row is skipped and its
// reference at most 2^e. The slots that have such a t do not change with e (it only moves the t).
void LaneAccumulator::set_drop_t(int e) {
  const std::vector<double> small = deferred_t(slots_, e);
  drop_t_.assign(tau_.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < tau_.size(); ++s) {
    if (s >= small.size() || small[s] <= 0.0 || tau_[s] < 0) continue;  // Gaussian, or none skipped
    const double t = std::min(small[s], skips_at_or_below(s));
    if (computes_at_or_below(s, t)) continue;  // a check beside the argument above
    drop_t_[s] = t;
    drops_any_ = true;
  }
}

int LaneAccumulator::deferred_exponent() const {
  return allowed_deferral_exponent(stats_.total.sum_sq, display_);
}

void LaneAccumulator::set_deferred_exponent(int e) {
  sum_settled_ = exponent_absorbed_by(stats_.total.sum_sq) >= e;
  if (e == deferred_exponent_) return;
  deferred_exponent_ = e;
  set_drop_t(e);
}

CodeFacts LaneAccumulator::compute_facts(std::size_t slot, std::int64_t t_raw) const {
  CodeFacts f;
  f.out = unit_.eval(slot, t_raw);
  const double t = static_cast<double>(t_raw) * in_ulp_;
  f.r = reference_value(slots_, slot, t);
  const double model = unit_.model(slot, t_raw);
  const double ideal = unit_.float_model(slot, t);
  f.approximation = ideal - f.r;
  f.parameter = model - ideal;
  f.datapath = static_cast<double>(f.out) * ulp_ - model;
  return f;
}

CodeFacts LaneAccumulator::facts(std::size_t slot, std::int64_t t_raw) const {
  if (!memo_ || memo_->tables[slot].size == 0) return compute_facts(slot, t_raw);
  const Memo::Table& table = memo_->tables[slot];
  const auto c = static_cast<std::size_t>(t_raw - table.first);
  const std::int64_t out = table.hot[c].out.load(std::memory_order_acquire);
  if (out == kUnset) return Memo::fill(table, c, compute_facts(slot, t_raw));
  const Memo::Parts& p = table.parts[c];
  return CodeFacts{out, table.hot[c].r.load(std::memory_order_relaxed),
                   p.approximation.load(std::memory_order_relaxed),
                   p.parameter.load(std::memory_order_relaxed),
                   p.datapath.load(std::memory_order_relaxed)};
}

void LaneAccumulator::add(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                          bool skipped, std::int64_t out_raw) {
  begin_slot(slot);
  const double fixed = static_cast<double>(out_raw) * ulp_;
  ++stats_.vectors;
  stats_.skipped += skipped;
  stats_.weighted.add(
      row_pixel_error(slots_.display == DisplayEncoding::kLinear8, slots_.pixel_weight[slot],
                      slots_.pixel_weight_max[slot], fixed, ref.value),
      ref.t);
  // A lobe that never reaches eps on the pixel is counted apart: its scalar error is the whole
  // lobe and would hide every other slot's (it stays in the weighted error and the digest).
  if (slot_state_[slot] == 1) {
    ++stats_.always_skipped_vectors;
  } else {
    add_scalar(slot, ref, t_raw, skipped, fixed);
  }
  digest_ = fold_digest(digest_, digest_word(out_raw, skipped));
}

void LaneAccumulator::add_scalar(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                                 bool skipped, double fixed) {
  stats_.total.add(fixed - ref.value, ref.t);
  if (skipped) {
    stats_.skip.add(ref.value, ref.t);
  } else {
    // The parts of a code are the same at every visit, so adding them at each visit keeps the
    // first row that reached the largest, as adding them at the code's first visit would.
    const CodeFacts f = facts(slot, t_raw);
    stats_.approximation.add(f.approximation, ref.t);
    stats_.parameter.add(f.parameter, ref.t);
    stats_.datapath.add(f.datapath, ref.t);
    stats_.input.add(f.r - ref.value, ref.t);
  }
  const long ref_code =
      ref.display_bits == stats_.display_bits ? ref.display : display_code(ref.value, display_);
  if (display_code(fixed, display_) != ref_code) ++stats_.mismatch;
}

namespace {

// What a run reads of its lane, filled by LaneAccumulator::accumulate_rows.
struct LaneView {
  const SlotMap& slots;
  InputQuantizer quantize;
  const std::int64_t* tau;      // per slot: the comparator's threshold
  const std::int8_t* state;     // per slot: 1 always skipped
  const double* drop_t;         // per slot (LaneAccumulator::drop_t)
  const double* settle_weight;  // per slot: slope x largest channel weight (SettledRows::weighted)
  double max_weight, ulp, display;
  bool any_always;  // some begun slot is always skipped
  SettledRows settled;
};

// One run of accumulate(): rows a .. b - 1 of a window, numbered 0 .. n - 1 in its lists. Its
// state is one local object, and its passes are inlined into accumulate_rows (a class of this file
// alone, each pass called once), so the maxima stay in registers: as members of an object the
// loops' stores may reach, they went through memory on every row (sim_speed 4-10 % more CPU time
// at the same instruction count, when the passes were members of a nested class of the lane).
// Memo and Facts: the lane's memo type and its compute_facts, which are private to it.
//
// The passes: every row's code and comparator (classify: the computed and the skipped rows listed
// without a branch between them, which a stream takes at random); the skipped rows' statistics
// (add_skipped_rows, or add_skipped_rows_leaving_out_dropped for a lane that may leave rows out);
// then the computed rows' (add_computed_rows). The maxima that both lists enter keep the row of
// their first largest value (FirstMax), to be joined as one pass in stream order would have.
template <class Memo, class Facts>
struct Run {
  Run(const LaneView& lane, const Memo* memo, const Facts& facts, const RowsView& rows,
      std::size_t a, std::size_t b, LanePartial& p)
      : lane(lane),
        memo(memo),
        facts(facts),
        rows(rows),
        a(a),
        n(b - a),
        p(p),
        tau(lane.tau),
        state(lane.state),
        weight(lane.slots.pixel_weight_max.data()),
        pixel_weight(lane.slots.pixel_weight.data()),
        settle_weight(lane.settle_weight),
        linear(lane.slots.display == DisplayEncoding::kLinear8),
        ulp(lane.ulp),
        display(lane.display),
        settled(lane.settled) {
    p.square.resize(n);
    p.word.resize(n);
    p.folded.clear();
    square = p.square.data();
    word = p.word.data();
    thread_local std::vector<std::uint32_t> computed_list, skipped_list, row_list;
    thread_local std::vector<std::int64_t> code_list;
    computed_list.resize(n);
    skipped_list.resize(n);
    row_list.resize(n);
    code_list.resize(n);
    computed = computed_list.data();
    skipped_rows = skipped_list.data();
    listed = row_list.data();
    code = code_list.data();
  }

  // Rows k0 .. k0 + count - 1, or those of `at` (not null), through classify_rows: the computed
  // ones appended to `computed` and `code`, the skipped ones listed from skipped_rows[0]; returns
  // how many were skipped.
  std::size_t classify(const std::uint32_t* at, std::size_t k0, std::size_t count) {
    const auto sort = [&](auto row_at) {
      return classify_rows(lane.quantize, rows.t + a, rows.slot + a, tau, row_at, count,
                           computed + computed_count, code + computed_count, skipped_rows, word);
    };
    const ClassifiedRows c =
        at ? sort([at](std::size_t x) { return at[x]; })
           : sort([k0](std::size_t x) { return static_cast<std::uint32_t>(k0 + x); });
    computed_count += c.computed;
    skipped_count += c.skipped;
    return c.skipped;
  }

  // The two halves of "settled" (SettledRows) on this run's maxima so far; add_skipped and the
  // filter of add_unsettled_skipped rely on judging rows alike.
  bool scalars_settled() const { return settled.scalars(skipped_total.value, skip.value); }

  // Skipped row k: its result is 0, so its error is its reference.
  void add_skipped(std::size_t k) {
    const std::size_t i = a + k;
    const std::size_t s = rows.slot[i];
    const double t = rows.t[i];
    double ref = rows.reference[i];
    const bool always = state[s] == 1;
    // A deferred reference that can change nothing goes through the statistics below as 0,
    // which changes nothing either (every maximum it enters is larger, its square is 0, its
    // display code 0): no branch on which rows were deferred, which a stream takes at random.
    const bool scalars = scalars_settled();
    const bool weighted = settled.weighted(skipped_weighted.value, settle_weight[s]);
    const bool is_settled = (always | scalars) & weighted;
    if ((ref < 0.0) & !is_settled) ref = reference_value(lane.slots, s, t);
    ref = select(ref < 0.0, 0.0, ref);  // kDeferredReference is negative, a lobe never
    skipped_weighted.add(skipped_pixel_error(linear, weight[s], ref), t, k);
    if (always) {
      ++always_rows;
      square[k] = 0;
    } else {
      skipped_total.add(ref, t, k);
      square[k] = ref * ref;
      max_at(skip, ref, t);
      // The result's display code is 0; the reference's is not when it rounds up from 0.5.
      mismatch += min1(ref) * display >= 0.5;
    }
  }

  // The skipped rows skipped_rows[x .. end - 1], once the scalar maxima are settled: a row of
  // reference 0, or deferred in a slot whose weighted maximum is settled, changes nothing but its
  // square (0) and the count of always-skipped rows, so it is counted at once; the others go
  // through add_skipped.
  void add_unsettled_skipped(std::size_t x, std::size_t end) {
    const double weighted_now = skipped_weighted.value;
    std::size_t live = 0;
    for (std::size_t y = x; y < end; ++y) {
      const std::size_t j = skipped_rows[y];
      const std::size_t i = a + j;
      const std::size_t s = rows.slot[i];
      const double ref = rows.reference[i];
      const bool weighted = settled.weighted(weighted_now, settle_weight[s]);
      const bool keep = (ref > 0.0) | ((ref < 0.0) & !weighted);
      square[j] = 0;
      always_rows += (state[s] == 1) & !keep;
      skipped_rows[live] = static_cast<std::uint32_t>(j);
      live += keep;
    }
    for (std::size_t y = 0; y < live; ++y) add_skipped(skipped_rows[y]);
  }

  // Rows between two looks at the maxima: they only grow, and settle within a few dozen rows on a
  // typical stream.
  static constexpr std::size_t kSettledCheck = 64;

  // Passes 1 and 2 for a lane that leaves no row out: every row classified, then the skipped rows
  // in order through add_skipped until the scalar maxima are settled, the rest filtered.
  void add_skipped_rows() {
    const std::size_t skipped = classify(nullptr, 0, n);
    std::size_t x = 0;
    for (; x < skipped; ++x) {
      if (x % kSettledCheck == 0 && scalars_settled()) break;
      add_skipped(skipped_rows[x]);
    }
    add_unsettled_skipped(x, skipped);
  }

  // Passes 1 and 2 for a lane with a drop_t: a chunk of rows at a time until the scalar maxima are
  // settled; from there, if every slot's weighted maximum is settled too, the rows at or below
  // their slot's drop_t are left out at once (leave_out_dropped), so that most of a mostly skipped
  // stream costs a few operations a row.
  void add_skipped_rows_leaving_out_dropped() {
    std::size_t k = 0;
    for (; k < n && !scalars_settled(); k = std::min(n, k + kSettledCheck)) {
      const std::size_t some = classify(nullptr, k, std::min(n, k + kSettledCheck) - k);
      for (std::size_t x = 0; x < some; ++x) add_skipped(skipped_rows[x]);
    }
    const bool drop = settled.weighted(skipped_weighted.value, lane.max_weight);
    const std::size_t rest = drop ? leave_out_dropped(k) : n - k;
    add_unsettled_skipped(0, classify(drop ? listed : nullptr, k, rest));
  }

  // Rows k .. n - 1: those at or below their slot's drop_t (skipped, reference at most the bound)
  // counted with their digest words and zero squares in bulk; the others listed in `listed`.
  // Returns how many were listed.
  std::size_t leave_out_dropped(std::size_t k) {
    const double* const drop_t = lane.drop_t;
    const std::size_t count = list_rows(rows.t + a, rows.slot + a, drop_t, k, n, listed);
    std::fill(word + k, word + n, digest_word(0, true));
    std::fill(square + k, square + n, 0.0);
    skipped_count += (n - k) - count;
    if (lane.any_always)
      for (std::size_t j = k; j < n; ++j) {
        const std::size_t s = rows.slot[a + j];
        always_rows += (rows.t[a + j] <= drop_t[s]) & (state[s] == 1);
      }
    return count;
  }

  // Every row's result 0 and skip flag 1, but the computed rows' (whose results
  // add_computed_rows writes).
  void write_skip_flags(std::int64_t* raw, std::uint8_t* skipped) const {
    if (raw) std::fill(raw + a, raw + a + n, 0);
    if (skipped) {
      std::fill(skipped + a, skipped + a + n, 1);
      for (std::size_t x = 0; x < computed_count; ++x) skipped[a + computed[x]] = 0;
    }
  }

  void fold_parts(const CodeFacts& f, double t) {
    max_at(approximation, std::fabs(f.approximation), t);
    max_at(parameter, std::fabs(f.parameter), t);
    max_at(datapath, std::fabs(f.datapath), t);
  }

  // Pass 3: the computed rows, their facts from the per-code memo (kMemo) or computed.
  template <bool kMemo>
  void add_computed_rows(std::int64_t* raw) {
    // How many computed rows ahead the memo entry is fetched: five lanes' tables of 2^15 codes
    // are beyond the L2 cache, and a row's entry is where its t falls. Without the prefetch,
    // sim_speed with every request computed took 35 % more CPU time and glint eval 10 %, for
    // 5 % and 1.4 % fewer instructions (tests/bench/RESULTS.md, "Issue 30").
    constexpr std::size_t kAhead = 8;
    for (std::size_t x = 0; x < computed_count; ++x) {
      if constexpr (kMemo) {
        if (x + kAhead < computed_count) {
          const auto& ahead = memo->tables[rows.slot[a + computed[x + kAhead]]];
          __builtin_prefetch(&ahead.hot[static_cast<std::size_t>(code[x + kAhead] - ahead.first)]);
        }
      }
      const std::size_t k = computed[x];
      const std::size_t i = a + k;
      const std::size_t s = rows.slot[i];
      const double t = rows.t[i];
      double ref = rows.reference[i];
      const std::int64_t t_raw = code[x];
      const bool always = state[s] == 1;
      if (ref < 0.0) ref = reference_value(lane.slots, s, t);
      std::int64_t out = 0;
      double r = 0;
      if constexpr (kMemo) {
        const auto& table = memo->tables[s];
        const auto c = static_cast<std::size_t>(t_raw - table.first);
        out = table.hot[c].out.load(std::memory_order_acquire);
        if (out == kUnset) {
          const CodeFacts f = Memo::fill(table, c, facts(s, t_raw));
          out = f.out;
          r = f.r;
        } else {
          r = table.hot[c].r.load(std::memory_order_relaxed);
        }
        if (!table.is_folded(c)) {
          const auto& mp = table.parts[c];
          fold_parts(CodeFacts{out, r, mp.approximation.load(std::memory_order_relaxed),
                               mp.parameter.load(std::memory_order_relaxed),
                               mp.datapath.load(std::memory_order_relaxed)},
                     t);
          p.folded.emplace_back(static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(c));
        }
      } else {
        const CodeFacts f = facts(s, t_raw);
        out = f.out;
        r = f.r;
        fold_parts(f, t);
      }
      const double fixed = static_cast<double>(out) * ulp;
      const double err = fixed - ref;
      computed_weighted.add(row_pixel_error(linear, pixel_weight[s], weight[s], fixed, ref), t, k);
      if (always) {
        ++always_rows;
        square[k] = 0;
      } else {
        computed_total.add(std::fabs(err), t, k);
        square[k] = err * err;
        max_at(input, std::fabs(r - ref), t);
        mismatch += display_code(fixed, display) != display_code(ref, display);
      }
      word[k] = digest_word(out, false);
      if (raw) raw[i] = out;
    }
  }

  // The run's counts and maxima into its partial (its squares and words are there already).
  void finish() {
    p.vectors = n;
    p.skipped = skipped_count;
    p.always_skipped = always_rows;
    p.mismatch = mismatch;
    p.total = FirstMax::join(skipped_total, computed_total);
    p.weighted = FirstMax::join(skipped_weighted, computed_weighted);
    p.input = input;
    p.skip = skip;
    p.approximation = approximation;
    p.parameter = parameter;
    p.datapath = datapath;
  }

  const LaneView& lane;
  const Memo* const memo;  // null: no memo (add_computed_rows<false>)
  const Facts& facts;
  const RowsView rows;
  const std::size_t a, n;
  LanePartial& p;
  const std::int64_t* const tau;
  const std::int8_t* const state;
  const double* const weight;         // per slot: the largest channel weight
  const Rgb* const pixel_weight;      // per slot: the channel weights
  const double* const settle_weight;  // per slot: LaneView::settle_weight
  const bool linear;                  // the display's encoding is linear
  const double ulp, display;
  const SettledRows settled;
  double* square = nullptr;
  std::uint64_t* word = nullptr;
  std::uint32_t* computed = nullptr;      // computed rows, in order
  std::int64_t* code = nullptr;           // their input codes
  std::uint32_t* skipped_rows = nullptr;  // skipped rows of the last classify, in order
  std::uint32_t* listed = nullptr;        // rows not left out (leave_out_dropped)
  std::size_t computed_count = 0, skipped_count = 0;
  FirstMax skipped_total, skipped_weighted, computed_total, computed_weighted;
  LanePartial::MaxAt input{0, 0}, skip{0, 0};
  LanePartial::MaxAt approximation{0, 0}, parameter{0, 0}, datapath{0, 0};
  std::uint64_t always_rows = 0, mismatch = 0;
};

}  // namespace

void LaneAccumulator::accumulate(const RowsView& rows, std::size_t a, std::size_t b, LanePartial& p,
                                 std::int64_t* raw, std::uint8_t* skipped) const {
  if (memo_) {
    accumulate_rows<true>(rows, a, b, p, raw, skipped);
  } else {
    accumulate_rows<false>(rows, a, b, p, raw, skipped);
  }
}

template <bool kMemo>
void LaneAccumulator::accumulate_rows(const RowsView& rows, std::size_t a, std::size_t b,
                                      LanePartial& p, std::int64_t* raw,
                                      std::uint8_t* skipped) const {
  const LaneView lane{
      slots_,
      InputQuantizer(unit_.in_format()),
      tau_.data(),
      slot_state_.data(),
      drop_t_.data(),
      settle_weight_.data(),
      max_weight_,
      ulp_,
      display_,
      any_always_,
      SettledRows(deferred_exponent_, sum_settled_),
  };
  const auto facts = [this](std::size_t slot, std::int64_t t_raw) {
    return compute_facts(slot, t_raw);
  };
  Run<Memo, decltype(facts)> run(lane, memo_.get(), facts, rows, a, b, p);
  if (drops_any_) {
    run.add_skipped_rows_leaving_out_dropped();
  } else {
    run.add_skipped_rows();
  }
  run.write_skip_flags(raw, skipped);
  run.template add_computed_rows<kMemo>(raw);
  run.finish();
}

void LaneAccumulator::merge_counts(const LanePartial& p) {
  stats_.vectors += p.vectors;
  stats_.skipped += p.skipped;
  stats_.always_skipped_vectors += p.always_skipped;
  stats_.mismatch += p.mismatch;
  merge_error(stats_.total, p.total, p.vectors - p.always_skipped);
  merge_error(stats_.weighted, p.weighted, p.vectors);
  merge_part(stats_.input, p.input);
  merge_part(stats_.parameter, p.parameter);
  merge_part(stats_.approximation, p.approximation);
  merge_part(stats_.datapath, p.datapath);
  merge_part(stats_.skip, p.skip);
  for (const auto& [slot, c] : p.folded) memo_->tables[slot].set_folded(c);
}

// kLanes lanes' folds at once, each lane's in its own order; in locals, as the stores would
// otherwise reload every member.
template <std::size_t kLanes>
void LaneAccumulator::fold_lanes(LaneAccumulator* const* lanes, const LanePartial* const* parts) {
  double sum[kLanes];
  std::uint64_t digest[kLanes];
  const double* square[kLanes];
  const std::uint64_t* word[kLanes];
  for (std::size_t j = 0; j < kLanes; ++j) {
    sum[j] = lanes[j]->stats_.total.sum_sq;
    digest[j] = lanes[j]->digest_;
    square[j] = parts[j]->square.data();
    word[j] = parts[j]->word.data();
  }
  const std::size_t n = parts[0]->word.size();
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < kLanes; ++j) fold_row(sum[j], digest[j], square[j][k], word[j][k]);
  for (std::size_t j = 0; j < kLanes; ++j) {
    lanes[j]->stats_.total.sum_sq = sum[j];
    lanes[j]->digest_ = digest[j];
  }
}

void LaneAccumulator::merge(const LanePartial& p, TimingEngine* timing) {
  merge_counts(p);
  double sum = stats_.total.sum_sq;
  std::uint64_t digest = digest_;
  const double* const square = p.square.data();
  const std::uint64_t* const word = p.word.data();
  const auto fold = [&](std::size_t k) { fold_row(sum, digest, square[k], word[k]); };
  if (timing) {
    timing->next_words(word, p.word.size(), fold);
  } else {
    for (std::size_t k = 0; k < p.word.size(); ++k) fold(k);
  }
  stats_.total.sum_sq = sum;
  digest_ = digest;
}

void LaneAccumulator::merge_group(LaneAccumulator* const* lanes, const LanePartial* const* parts,
                                  TimingEngine* const* timing, std::size_t count) {
  static_assert(kMergeGroup == 4, "the switch below folds up to 4 lanes at once");
  for (std::size_t at = 0; at < count; at += kMergeGroup) {
    const std::size_t size = std::min(kMergeGroup, count - at);
    if (size == 1) {
      lanes[at]->merge(*parts[at], timing[at]);
      continue;
    }
    for (std::size_t j = at; j < at + size; ++j) lanes[j]->merge_counts(*parts[j]);
    switch (size) {
      case 2:
        fold_lanes<2>(lanes + at, parts + at);
        break;
      case 3:
        fold_lanes<3>(lanes + at, parts + at);
        break;
      default:
        fold_lanes<4>(lanes + at, parts + at);
        break;
    }
    for (std::size_t j = at; j < at + size; ++j)
      if (timing[j]) timing[j]->next_words(parts[j]->word.data(), parts[j]->word.size());
  }
}

}  // namespace glint
