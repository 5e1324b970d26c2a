// Untimed evaluation of units over a vector stream: slots from the header, the float reference per
// request, and the statistics every report carries (the model error and the datapath error kept
// apart, as the accuracy contract asks).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "eval/contract.h"
#include "eval/deferral.h"
#include "io/vectors.h"
#include "reference/pixel_error.h"
#include "reference/reference.h"
#include "timing/timing.h"
#include "units/catalogue.h"
#include "units/chip.h"
#include "units/slot_plan.h"

namespace glint {

// How the stream's (light, material) pairs map to unit slots and datapath groups (units/
// slot_plan.h): one slot per distinct (material, c_y), c_y = luminance(light x specular)
// (Källberg & Larsson eq.3; eq.6 for white lights), so lights that leave a material's c_y unchanged
// share its slot; one datapath group per material (materials whose datapaths would be identical
// share one), built for the smallest tau of its slots.
struct SlotMap : SlotPlan {
  std::vector<Lobe> lobe;         // lobe of each slot's material
  std::vector<double> roughness;  // gaussian omega (0 otherwise)
  // The weight behind each slot's tau (eq.5: tau = (eps_K / weight)^(1/n)): c_y, the luminance of
  // light x specular (eq.3), or with EpsMeasure::kChannel the largest channel weight.
  std::vector<double> c_y;
  // Each slot's channel weights on the pixel (reference/pixel_error.h), and the largest: the
  // weighted error's factor. Lights that share a slot (the same c_y) with different colours give
  // it the largest of their weights per channel, a bound on each request's.
  std::vector<Rgb> pixel_weight;
  std::vector<double> pixel_weight_max;
  DisplayEncoding display = DisplayEncoding::kLinear8;  // the stream's (the header's `display`)
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  // The largest pixel_weight_max / c_y over the slots (1 with EpsMeasure::kChannel): a skipped
  // lobe reaches at most eps_K times it on a channel (skip_guarantee_lsb).
  double skip_ratio = 1;
  bool per_light = false;  // some light changes some material's c_y: it has several slots
  std::size_t materials = 0;
  // The slot of (light, material) is slot_of[light * light_stride + material]; light_stride is 0
  // when every light gives each material the same slot.
  std::vector<std::uint32_t> slot_of;
  std::size_t light_stride = 0;

  std::size_t slot(const VectorRow& row) const {
    return slot_in(slot_of.data(), light_stride, row);
  }
  // The same from a copy of slot_of's data and light_stride (a hot loop keeps them in locals,
  // where stores through its other pointers cannot make the compiler reload them).
  static std::size_t slot_in(const std::uint32_t* slot_of, std::size_t light_stride,
                             const VectorRow& row) {
    return slot_of[light_stride * static_cast<std::size_t>(row.light) + row.material];
  }
};

// A stream that needs more slots or materials than a chip of given capacity holds.
class SlotCapacityError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Limits that keep a run's memory and time bounded and proportional to its input
// (src/cli/README.md, "Limits and guarantees"); a stream or run beyond them is refused with
// ResourceLimitError, whose message names the limit (the CLI reports it against the input file,
// exit 2).
//
// Slots of one stream, one per (material, c_y): each unit keeps ~15 KB per slot (its threshold,
// the slot's contract, accumulators and the elaboration's entries), so 65536 slots are ~1 GB per
// unit. The vector format's limit on materials is the same number, so only lights that change
// many materials' c_y reach it.
inline constexpr std::size_t kMaxStreamSlots = 65536;
// Light x material pairs of one stream: make_slots visits each, and every unit's elaboration
// lists each slot's lights (SlotOrigin::lights, the report's slot_list), ~70 bytes per pair and
// unit (measured: 64 white lights x 65536 materials, one unit, 850 MB peak against 560 MB under
// one light). 2^22 keeps that under ~300 MB per unit: 64 lights x 65536 materials, or 1024 lights
// x 4096 materials; the vector format alone would allow 2^26 (1024 x 65536: 5.3 GB and 25 s for
// one unit on a 3.6 MB file).
inline constexpr std::size_t kMaxLightMaterialPairs = std::size_t{1} << 22;
// Units x slots of one run: the default five units on the largest stream (measured: ~5 GB and
// ~1 min for `glint eval` of 65536 distinct materials).
inline constexpr std::size_t kMaxLaneSlots = 5 * kMaxStreamSlots;
// Input codes the accuracy contracts of one run sweep, over every unit (contract.h: every code each
// slot's comparator keeps, at most 2^20 + 1 per slot; slots with the same datapath, threshold and
// lobe share one sweep): 50-160 ns per code by unit, so about 1-3 min at the limit.
inline constexpr std::uint64_t kMaxContractCodes = std::uint64_t{1} << 30;
// Each lane memoises the facts of the input codes above each slot's threshold that it meets
// (LaneAccumulator, lane.cpp), for inputs of at most kMemoMaxWidth bits and at most
// kMemoMaxCodes codes over the unit's slots (beyond, every request computes its own): up to
// kMemoBytesPerCode bytes per code and 2^F + 1 codes per slot for F fraction bits, about 1.3 MB
// per slot at in=uq1.15 and 168 MB per lane at most. A run's lanes may take at most
// kMaxMemoBytes by that bound (measured: 8 pow lanes over 64 slots of shininess near 1, 674 MB
// against 671 MB by the bound; 64 lanes would be 5.4 GB).
inline constexpr int kMemoMaxWidth = 16;
inline constexpr std::size_t kMemoMaxCodes = std::size_t{1} << 22;
inline constexpr std::uint64_t kMemoBytesPerCode = 40;
inline constexpr std::uint64_t kMaxMemoBytes = std::uint64_t{4} << 30;

class ResourceLimitError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Refuses (ResourceLimitError) a run of `units` units over `slots` beyond kMaxLaneSlots.
void check_lane_slots(std::size_t units, const SlotMap& slots);

// The input codes the contracts of `unit` sweep when every slot is used (the cost of its
// LaneAccumulator), and the refusal (ResourceLimitError) of units whose sum exceeds
// kMaxContractCodes, naming each unit's share. Checked before any row is read.
std::uint64_t contract_codes(const SpecularUnit& unit, const SlotMap& slots);
void check_contract_codes(const std::vector<const SpecularUnit*>& units, const SlotMap& slots);

// The most a lane's memo takes for inputs of format `in` over `slots` slots (0: not memoised),
// and the refusal (ResourceLimitError) of units whose sum exceeds kMaxMemoBytes. Checked before
// any row is read.
std::uint64_t memo_bytes(const QFormat& in, std::size_t slots);
void check_memo_bytes(const std::vector<const SpecularUnit*>& units);

// The slots of a stream (above); eps is divided by the light count (Källberg §2, eps_n = eps/n).
// A chip of given capacity (units/chip.h: --chip ram:materials=M,slots=S) must hold the stream's
// slots and datapath groups (SlotCapacityError otherwise, with the counts); without one the lanes
// are sized to the stream. A stream that needs more than kMaxStreamSlots slots is refused
// (ResourceLimitError).
SlotMap make_slots(const VectorHeader& header, const Chip& chip = {});

// The header with the run's eps measure (--eps-measure): make_slots keys slots and thresholds on
// it.
inline VectorHeader with_eps_measure(VectorHeader header, EpsMeasure measure) {
  header.eps_measure = measure;
  return header;
}

// What every report states of its pixel measure (reference/pixel_error.h): the display encoding
// and the eps measure, as text for a summary line ("pixel error: ...", no newline) and as JSON.
std::string pixel_measure_line(const SlotMap& slots);
nlohmann::json pixel_measure_json(const SlotMap& slots);

// The float reference the units are judged against: max(0,t)^n for Phong and Blinn (eq.1-2, the
// scalar lobe; colour is a separate multiply), exp(-(acos t / omega)^2) for Gaussian lobes (eq.7),
// at t clamped to <= 1.
double reference_value(const SlotMap& slots, std::size_t slot, double t);

struct ErrorStats {
  double max_abs = 0;
  double t_at_max = 0;
  double sum_sq = 0;
  std::uint64_t count = 0;

  void add(double err, double t) {
    const double a = err < 0 ? -err : err;
    if (count == 0 || a > max_abs) {
      max_abs = a;
      t_at_max = t;
    }
    sum_sq += err * err;
    ++count;
  }
  double rms() const;
  nlohmann::json to_json() const;
};

// The largest observed |error| of one part (contract.h) and where it was.
struct PartStats {
  double max_abs = 0;
  double t_at_max = 0;
  void add(double err, double t) {
    const double a = err < 0 ? -err : err;
    if (a > max_abs) {
      max_abs = a;
      t_at_max = t;
    }
  }
};

struct UnitStats {
  std::string name, spec;
  nlohmann::json description;
  std::uint64_t vectors = 0, skipped = 0;
  std::uint64_t always_skipped_vectors = 0;  // of always-skipped slots: in no scalar statistic
  ErrorStats total;  // fixed result vs the reference lobe at the real t (what a user sees)
  // The pixel error (reference/pixel_error.h): the result's error on the largest channel of the
  // light x specular colour, in the display's encoding (linear: |error| x the largest channel
  // weight).
  ErrorStats weighted;
  // Observed parts (contract.h): input, parameter, approximation and datapath on computed
  // requests, skip (the lobe's value) on skipped ones.
  PartStats input, parameter, approximation, datapath, skip;
  double out_ulp = 1;  // the output format's ulp: the datapath part in ulps is datapath / out_ulp
  int display_bits = 8;
  std::uint64_t mismatch = 0;  // the display code of the result differs from the reference's
  // The contracts of the slots the stream used, always-skipped ones included (reported apart).
  std::vector<SlotContract> slots;

  // Bounds over the computed slots (always-skipped ones apart), and the weakest datapath contract.
  ErrorParts bound() const;
  double weighted_bound() const;  // over every slot, always-skipped ones included
  // Whether bound() is a bound: false when some computed slot's parts are estimates, measured at
  // sampled codes of an input finer than kExactInputBits that the enclosure could not certify
  // (SlotContract::exact; "~" in text tables).
  bool bound_exact() const;
  ContractKind contract() const;
  // The datapath part in output ulps (fixed result vs the unit's own real model).
  double max_ulps() const { return datapath.max_abs / out_ulp; }
  nlohmann::json errors_json() const;  // the "errors" object of eval and sim reports
  nlohmann::json to_json() const;
};

// The float reference of one request, computed once and shared by every lane.
struct RowReference {
  double t = 0;
  double value = 0;      // reference_value(): max(0,t)^n or the Gaussian lobe
  long display = 0;      // round(value (2^display_bits - 1)): its display code
  int display_bits = 8;  // lanes with another depth compute their own code
};
RowReference make_reference(const SlotMap& slots, std::size_t slot, double t, int display_bits = 8);

// What the computed path of one (slot, input code) always gives: the datapath's result, the lobe
// at the code's value r(t_c), and the parameter, approximation and datapath parts (contract.h),
// signed. They depend on the code alone, so a lane works them out once per code for narrow inputs.
struct CodeFacts {
  std::int64_t out = 0;                                   // eval(slot, code)
  double r = 0;                                           // reference_value at the code's value
  double approximation = 0, parameter = 0, datapath = 0;  // F - r, M - F, fixed - M
};

// The statistics of a run of consecutive rows of one lane, worked out on any thread and merged
// into the lane in stream order (LaneAccumulator::accumulate, merge). Everything here is a count
// or a largest value with the first row that reached it, so partials merge exactly; the sum of
// squares and the digest are sequential folds, so the partial keeps each row's term for the
// merge to fold in order.
struct LanePartial {
  struct MaxAt {
    double value, t;
  };
  std::uint64_t vectors = 0, skipped = 0, always_skipped = 0, mismatch = 0;
  MaxAt total{-1, 0}, weighted{-1, 0};  // -1: no row yet (ErrorStats: its first row sets it)
  MaxAt input{0, 0}, parameter{0, 0}, approximation{0, 0}, datapath{0, 0}, skip{0, 0};
  std::vector<double> square;       // per row: err^2 (0 for rows in no scalar statistic)
  std::vector<std::uint64_t> word;  // per row: the digest word (skip flag in bit 63)
  // Memoised (slot, code) pairs whose parts these rows folded, first seen before this window.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> folded;
};

// The rows of a window, prepared once for every lane: t, slot and the float reference, or
// kDeferredReference where the lobe is at most the window's deferral bound (2^e, e the exponent
// the engine gave every lane: LaneAccumulator::set_deferred_exponent) and no lane may need its
// value (a lane computes it when it does: LaneAccumulator::accumulate).
struct RowsView {
  const double* t = nullptr;
  const std::uint32_t* slot = nullptr;
  const double* reference = nullptr;
};
// Accuracy statistics of one lane (a unit): fed one result at a time by `glint eval --dump`
// and the clocked mode's scoreboard (add), or a run of rows at a time by the evaluation engine
// (eval/engine.h: begin_slot, accumulate on any thread, merge in stream order). One accumulation
// for every path: the results are the same bits either way.
class LaneAccumulator {
 public:
  LaneAccumulator(const SpecularUnit& unit, const SlotMap& slots, int display_bits = 8);
  LaneAccumulator(LaneAccumulator&&) noexcept;
  ~LaneAccumulator();

  // What a slot's contract depends on besides its name and weight: its datapath group, its
  // threshold, its lobe (kind, shininess, roughness) and whether it is always skipped. Slots with
  // one key share one contract sweep.
  using ContractKey = std::tuple<std::size_t, std::int64_t, int, double, double, bool>;

  void add(std::size_t slot, const RowReference& ref, std::int64_t t_raw, bool skipped,
           std::int64_t out_raw);
  // A digest of every (skipped, out_raw) in stream order: bit-accurate regression in 64 bits.
  std::uint64_t digest() const { return digest_; }
  const UnitStats& stats() const { return stats_; }
  UnitStats& stats() { return stats_; }

  // The engine's side. A slot's first use (its contract, in stream order); then rows [a, b) of a
  // window into `p` (const: any number of threads at once, on disjoint partials), their results
  // into raw/skipped (when not null, indexed from a); then merge() of the partials in order.
  void begin_slot(std::size_t slot);
  bool slot_begun(std::size_t slot) const { return slot_state_[slot] >= 0; }
  // Whether the comparator of `slot` keeps some t at or below `t` (computes its row).
  bool computes_at_or_below(std::size_t slot, double t) const;
  // The largest t at or below which this lane skips the rows of `slot` and their reference is at
  // most the deferral bound (set_deferred_exponent); -inf for none (a Gaussian lobe, a slot whose
  // comparator skips nothing).
  double drop_t(std::size_t slot) const { return drop_t_[slot]; }
  // The largest deferral exponent e this lane's statistics allow from here on: a skipped row
  // whose reference is at most 2^e changes nothing once the maxima are above it, its square being
  // below half an ulp of the sum of squares so far (which only grows) and its display code 0. At
  // least kDeferredExponent (which a run's own rows settle). Read between windows (no merge
  // running).
  int deferred_exponent() const;
  // The deferral exponent of the next windows (the engine's, at most every lane's
  // deferred_exponent()): deferred references are at most 2^e, and the rows this lane skips at or
  // below 2^e are left out once settled. Between windows only (no accumulate running).
  void set_deferred_exponent(int e);
  void accumulate(const RowsView& rows, std::size_t a, std::size_t b, LanePartial& p,
                  std::int64_t* raw, std::uint8_t* skipped) const;
  // With `timing` (may be null), the partial's skip pattern through the lane's timing
  // recurrences too, in the same loop as the lane's sequential folds: each is a chain of dependent
  // operations, which alone leaves the core mostly idle.
  void merge(const LanePartial& p, TimingEngine* timing = nullptr);
  // merge() of parts[j] into lanes[j] (timing[j]: may be null) for j < count, the sequential
  // folds of up to kMergeGroup lanes side by side.
  static constexpr std::size_t kMergeGroup = 4;
  static void merge_group(LaneAccumulator* const* lanes, const LanePartial* const* parts,
                          TimingEngine* const* timing, std::size_t count);

 private:
  struct Memo;
  // The facts of (slot, code), from the memo for narrow inputs (filled on first use; safe from
  // any thread), computed otherwise.
  CodeFacts facts(std::size_t slot, std::int64_t t_raw) const;
  void merge_counts(const LanePartial& p);  // merge() but for the sequential folds
  template <std::size_t kLanes>
  static void fold_lanes(LaneAccumulator* const* lanes, const LanePartial* const* parts);
  template <bool kMemo>
  void accumulate_rows(const RowsView& rows, std::size_t a, std::size_t b, LanePartial& p,
                       std::int64_t* raw, std::uint8_t* skipped) const;
  CodeFacts compute_facts(std::size_t slot, std::int64_t t_raw) const;
  void add_scalar(std::size_t slot, const RowReference& ref, std::int64_t t_raw, bool skipped,
                  double fixed);
  ContractKey contract_key(std::size_t slot) const;

  const SpecularUnit& unit_;
  const SlotMap& slots_;
  UnitStats stats_;
  std::uint64_t digest_ = 0xcbf29ce484222325ULL;
  double ulp_ = 0, in_ulp_ = 0, display_ = 0;
  std::vector<std::int64_t> tau_;  // each slot's comparator threshold
  // Per slot: -1 not seen yet (its contract not computed), 0 computed, 1 always skipped.
  std::vector<std::int8_t> slot_state_;
  // Contracts already swept, by what they depend on (contract_key): slots of one datapath group
  // with the same threshold and lobe share one sweep (a file of many identical materials).
  std::map<ContractKey, std::size_t> contract_of_;  // index into stats_.slots
  std::unique_ptr<Memo> memo_;                      // null: inputs too wide to memoise
  // The deferral bound 2^e of the current windows (set_deferred_exponent), and whether the sum
  // of squares before them already puts the bound's square below half its ulp (else a run's own
  // rows must: accumulate_rows).
  int deferred_exponent_ = kDeferredExponent;
  bool sum_settled_ = false;
  // Per slot, the largest t at or below which a row is skipped and its reference at most the
  // deferral bound (-inf: none; accumulate_rows leaves such rows out once its statistics are
  // settled); whether any slot has one, whether some begun slot is always skipped, and per slot and
  // over all the factor a deferred reference's pixel error is at most (slope x w_max).
  std::vector<double> drop_t_;
  bool drops_any_ = false, any_always_ = false;
  std::vector<double> settle_weight_;
  double max_weight_ = 0;
  void set_drop_t(int e);
  // The largest t the comparator of `slot` surely skips (the value of its threshold's code;
  // -inf when it skips nothing).
  double skips_at_or_below(std::size_t slot) const;
};

// One evaluated request for the optional per-vector dump.
struct EvalRecord {
  const VectorRow* row;
  std::size_t unit;
  std::int64_t t_raw;
  double reference, model, fixed;
  std::int64_t fixed_raw;
  bool skipped;
};

// Schema version of the `glint eval` JSON report (key "glint_eval_report", schema in
// src/eval/eval_report.md). Version 1 is the unversioned layout before eval took `glint sim`'s key
// names (error_vs_reference, datapath_error_ulps, top-level mismatch_8bit_fraction and
// error_bound); 2 nests them in "errors"; 3 decomposes them (errors.parts, bounds per slot, display
// and weighted errors, contract); 4 adds the scene's elaboration (datapath_groups, slot_capacity,
// description.elaboration); 5 states the chip (chip replaces slot_capacity; elaboration.storage,
// group_capacity); 6 states the pixel measure (pixel_measure: display, eps_measure) and makes the
// weighted errors the pixel error of reference/pixel_error.h (5: the scalar error times c_y).
inline constexpr int kEvalReportVersion = 6;

// The results of one batch of rows through every unit of an Evaluator: unit u's result for row i
// at raw[u * rows + i] (0 when skipped), its skip flag at skipped[u * rows + i], and the float
// reference of row i at reference[i].
struct BatchResults {
  std::size_t rows = 0;
  std::vector<double> reference;
  std::vector<std::int64_t> raw;
  std::vector<std::uint8_t> skipped;
};

class EvalEngine;

class Evaluator {
 public:
  // The units as lanes of `chip` (specs_on_chip, make_slots).
  Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs, int display_bits = 8,
            const Chip& chip = {});
  ~Evaluator();

  void add(const VectorRow& row, const std::function<void(const EvalRecord&)>& dump = {});
  // The same as add() on each row in turn, through the evaluation engine (eval/engine.h) on up to
  // `threads` threads: statistics, digests and results are identical for any thread count.
  void add_batch(const VectorRow* rows, std::size_t count, BatchResults& out, int threads = 1);
  // The same without the per-row results. `side` (may be empty): work done beside the rows, a
  // step per call while it returns true (EvalEngine::add), on one thread at a time.
  void add_rows(const VectorRow* rows, std::size_t count, int threads = 1,
                const std::function<bool()>& side = {});
  // Whether add_rows on `threads` threads runs its side work beside the rows (else before them).
  bool overlaps_side_work(int threads) const;
  std::vector<UnitStats> stats() const;
  const std::string& label(std::size_t unit) const { return lanes_[unit].stats().name; }
  // The digest of unit u's results so far (LaneAccumulator::digest; sim reports it as "digest").
  std::uint64_t digest(std::size_t unit) const { return lanes_[unit].digest(); }
  // Unit u's lane, for an engine that runs it with others (sweep/engine.h).
  LaneAccumulator& lane(std::size_t unit) { return lanes_[unit]; }
  const std::vector<std::unique_ptr<SpecularUnit>>& units() const { return units_; }
  const SlotMap& slots() const { return slots_; }
  const Chip& chip() const { return chip_; }
  // The report's version, slots, chip and units (the caller adds vectors_file and rows).
  nlohmann::json to_json() const;

 private:
  SlotMap slots_;
  Chip chip_;
  std::vector<std::unique_ptr<SpecularUnit>> units_;
  std::vector<LaneAccumulator> lanes_;
  int display_bits_ = 8;
  void run_engine(const VectorRow* rows, std::size_t count, BatchResults* out, int threads,
                  const std::function<bool()>& side = {});
  std::unique_ptr<EvalEngine> engine_;  // made by the first add_batch or add_rows
  int engine_threads_ = 0;
};

// One line per unit of what the scene elaborated (slots, datapath groups, table entries, n
// register), printed by `glint eval` after its tables.
std::string format_elaboration(const std::vector<UnitStats>& stats);

// The summary table printed by `glint eval`, and the table of error parts printed after it.
// The note under a text table that marks an estimated bound "~" (eval's, size's, sweep's).
inline constexpr const char* kEstimateNote =
    "~ an estimate, not a bound: sampled codes of an input finer than 2^-20, for a unit whose "
    "models are not known to be monotone\n";

std::string format_eval_table(const std::vector<UnitStats>& stats);
std::string format_parts_table(const std::vector<UnitStats>& stats);

}  // namespace glint
