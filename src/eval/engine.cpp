#include "eval/engine.h"

#include <algorithm>
#include <limits>
#include <mutex>

namespace glint {
namespace {

// Rows per run below which splitting a lane's window costs more than it brings.
constexpr std::size_t kMinRunRows = 4096;
// Rows of a span, prepared at once (~20 bytes a row) when lanes take whole windows on several
// threads: enough windows that the threads rarely meet at its end.
constexpr std::size_t kSpanRows = 262144;

std::size_t ceil_div(std::size_t a, std::size_t b) {
  return (a + b - 1) / b;
}

// What prepare's scan reads and writes, as plain pointers in a function of its own (scan_rows):
// as a lambda's captures, GCC kept them on the stack and reloaded them on every row.
struct RowScan {
  const VectorRow* rows;
  const std::uint32_t* slot_of;
  std::size_t light_stride;
  const double* deferred;   // per slot (deferred_t)
  const double* defer_cut;  // the same, 0 where some lane computes such rows
  const std::uint8_t* known;
  bool defer;  // no per-row results asked: small references may be left to the lanes
  double* t_out;
  std::uint32_t* slot_out;
  double* ref_out;
  std::uint32_t* need;
};

// Rows [a, b): each row's t and slot, its reference's placeholder, and the rows whose reference is
// computed listed in `need` (returns how many); `unknown` is set if a slot no lane has begun is
// among them.
std::size_t scan_rows(const RowScan& scan, std::size_t a, std::size_t b, bool& unknown) {
  const VectorRow* const __restrict rows = scan.rows;
  const std::uint32_t* const __restrict slot_of = scan.slot_of;
  const std::size_t stride = scan.light_stride;
  const double* const __restrict deferred = scan.deferred;
  const double* const __restrict defer_cut = scan.defer_cut;
  const std::uint8_t* const __restrict known = scan.known;
  const bool defer = scan.defer;
  double* const __restrict t_out = scan.t_out;
  std::uint32_t* const __restrict slot_out = scan.slot_out;
  double* const __restrict ref_out = scan.ref_out;
  std::uint32_t* const __restrict need = scan.need;
  std::size_t needed = 0;
  bool all_known = true;
  // The rows are usually beyond the core's cache (a block of a quarter of a million rows, filled
  // by the reader's threads): fetched 2 KiB ahead, which the hardware's prefetcher, stopping at
  // every 4 KiB page, does not do on its own. Without it sim_speed took 6-8 % more CPU time and
  // glint eval 3 % (medians of 7 alternating runs; tests/bench/RESULTS.md, "Issue 30").
  // The address is worked out as an integer: past the block's end it is only a hint.
  constexpr std::uintptr_t kAhead = 64 * sizeof(VectorRow);
  for (std::size_t i = a; i < b; ++i) {
    __builtin_prefetch(
        reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(rows + i) + kAhead));
    const auto s = static_cast<std::uint32_t>(SlotMap::slot_in(slot_of, stride, rows[i]));
    const double t = rows[i].t;
    t_out[i] = t;
    slot_out[i] = s;
    // deferred[s] > 0: a power lobe, which is 0 at t <= 0. A reference far below what any
    // statistic can see is left to the lane that needs it (LaneAccumulator::accumulate): on a
    // stream of mostly skipped requests, most of them.
    const double cut = deferred[s];
    const bool zero = (cut > 0.0) & (t <= 0.0);
    const bool late = defer & (t > 0.0) & (t <= defer_cut[s]);
    // -late, not late ? kDeferredReference : 0.0, which GCC made a branch taken at random:
    // sim_speed's skipped stream took 42 % more CPU time with it (tests/bench/RESULTS.md).
    static_assert(kDeferredReference == -1.0, "the conversion below writes -1 or 0");
    ref_out[i] = -static_cast<double>(late);
    need[needed] = static_cast<std::uint32_t>(i);
    needed += !(zero | late);
    all_known &= known[s] != 0;
  }
  unknown = !all_known;
  return needed;
}

// Lane l's results from the stream's row `offset` of an add(), when they are asked for.
std::int64_t* raw_at(BatchResults* out, std::size_t l, std::size_t offset) {
  return out ? out->raw.data() + l * out->rows + offset : nullptr;
}
std::uint8_t* skipped_at(BatchResults* out, std::size_t l, std::size_t offset) {
  return out ? out->skipped.data() + l * out->rows + offset : nullptr;
}

}  // namespace

EvalEngine::EvalEngine(const SlotMap& slots, std::vector<LaneAccumulator*> lanes,
                       std::vector<TimingEngine*> timing, const EngineOptions& options)
    : slots_(slots),
      lanes_(std::move(lanes)),
      timing_(std::move(timing)),
      options_(options),
      pool_(std::max(1, options.threads)) {
  if (timing_.empty()) timing_.assign(lanes_.size(), nullptr);
  options_.window_rows = std::max<std::size_t>(1, options_.window_rows);
  slot_known_.assign(slots.params.size(), 0);
  deferred_t_ = deferred_t(slots);
  for (auto& p : partials_) p.resize(lanes_.size());
}

EvalEngine::~EvalEngine() = default;

bool EvalEngine::overlaps_side_work(std::size_t lanes, int threads) {
  return threads > 1 && lanes >= 2 * static_cast<std::size_t>(threads);
}

// Enough lanes keep every thread busy with whole windows (no partials kept across tasks).
bool EvalEngine::whole_windows() const {
  return options_.run_rows == 0 &&
         (pool_.threads() == 1 || overlaps_side_work(lanes_.size(), pool_.threads()));
}

std::size_t EvalEngine::runs_per_lane(std::size_t count) const {
  if (options_.run_rows > 0) return ceil_div(count, options_.run_rows);
  if (whole_windows()) return 1;
  // Each run goes through every lane in one task (add_window): four tasks per thread whatever the
  // lanes, so that the last to finish waits little.
  const std::size_t runs = 4 * static_cast<std::size_t>(pool_.threads());
  return std::max<std::size_t>(1, std::min(runs, count / kMinRunRows));
}

void EvalEngine::add(const VectorRow* rows, std::size_t count, BatchResults* out,
                     const SideWork& side) {
  add_rows(rows, count, out, side, true);
}

void EvalEngine::add_open(const VectorRow* rows, std::size_t count) {
  add_rows(rows, count, nullptr, {}, false);
}

void EvalEngine::finish() {
  merge_pending();
}

void EvalEngine::add_rows(const VectorRow* rows, std::size_t count, BatchResults* out,
                          const SideWork& side, bool complete) {
  bool side_more = static_cast<bool>(side);
  if (!lanes_.empty()) {  // else a shard without configurations
    if (out) {
      out->rows = count;
      out->reference.resize(count);
      out->raw.resize(lanes_.size() * count);
      out->skipped.resize(lanes_.size() * count);
    }
    const std::size_t window = options_.window_rows;
    if (options_.run_rows == 0 && overlaps_side_work(lanes_.size(), pool_.threads())) {
      // Spans of equal size, at most twice kSpanRows: a short last span would end in a few
      // windows that the threads cannot share.
      const std::size_t spans = std::max<std::size_t>(1, count / kSpanRows);
      const std::size_t span = ceil_div(ceil_div(count, spans), window) * window;
      for (std::size_t at = 0; at < count; at += span)
        add_span(rows + at, std::min(span, count - at), at, out, side, side_more);
    } else {
      while (side_more) side_more = side();
      for (std::size_t at = 0; at < count; at += window)
        add_window(rows + at, std::min(window, count - at), at, out);
      if (complete) merge_pending();
    }
  }
  while (side_more) side_more = side();
}

void EvalEngine::merge(const std::vector<LanePartial>& runs, std::size_t l) {
  for (const LanePartial& p : runs) lanes_[l]->merge(p, timing_[l]);
}

void EvalEngine::merge_pending() {
  if (!pending_) return;
  const auto& last = partials_[1 - current_];
  pool_.run(lanes_.size(), [&](std::size_t l) { merge(last[l], l); });
  pending_ = false;
}

// Rows [a, b) of a window's `count` (its first in t_, slot_ and reference_ at index `at`): each
// row's slot and reference; the slots among them that no lane has begun go to `fresh` in the
// order of their first rows (the caller begins them: begin_fresh).
void EvalEngine::prepare_run(const VectorRow* rows, std::size_t a, std::size_t b,
                             std::size_t offset, BatchResults* out, std::size_t at,
                             std::vector<std::uint32_t>& fresh) {
  double* const t_out = t_.data() + at;
  std::uint32_t* const slot_out = slot_.data() + at;
  double* const ref_out = reference_.data() + at;
  // Rows whose reference is computed, listed: the calls then run back to back in a loop of their
  // own, where they overlap, instead of one in the middle of each scanned row.
  thread_local std::vector<std::uint32_t> need_list;
  need_list.resize(b - a);
  RowScan scan{rows,
               slots_.slot_of.data(),
               slots_.light_stride,
               deferred_t_.data(),
               deferral_.defer_t().data(),
               slot_known_.data(),
               out == nullptr,
               t_out,
               slot_out,
               ref_out,
               need_list.data()};
  bool unknown = false;
  const std::size_t needed = scan_rows(scan, a, b, unknown);
  const std::uint32_t* const need = need_list.data();
  if (unknown) {
    // Slots no lane has begun (rare: a slot's first window).
    std::vector<bool> listed(slot_known_.size());
    for (std::size_t i = a; i < b; ++i) {
      const std::uint32_t s = slot_out[i];
      if (!slot_known_[s] && !listed[s]) {
        listed[s] = true;
        fresh.push_back(s);
      }
    }
  }
  for (std::size_t x = 0; x < needed; ++x) {
    const std::size_t i = need[x];
    ref_out[i] = reference_value(slots_, slot_out[i], t_out[i]);
  }
  if (out) std::copy(ref_out + a, ref_out + b, out->reference.begin() + offset + a);
}

// The slots of `fresh` (per run, in stream order) begun in every lane, in that order; returns
// whether there were any.
bool EvalEngine::begin_fresh(const std::vector<std::vector<std::uint32_t>>& fresh) {
  std::vector<std::uint32_t> begun;
  for (const auto& list : fresh)
    for (const std::uint32_t s : list)
      if (!slot_known_[s]) {
        slot_known_[s] = 1;
        begun.push_back(s);
      }
  if (begun.empty()) return false;
  pool_.run(lanes_.size(), [&](std::size_t l) {
    for (const std::uint32_t s : begun) lanes_[l]->begin_slot(s);
  });
  return true;
}

// Each row's slot and reference, on the threads, into t_, slot_ and reference_ from index `at`
// (the caller sizes them); then the slots this window uses first, begun in every lane in the order
// of their first rows.
void EvalEngine::prepare(const VectorRow* rows, std::size_t count, std::size_t offset,
                         BatchResults* out, std::size_t at) {
  const std::size_t runs = std::max<std::size_t>(
      1, std::min(ceil_div(count, kMinRunRows), 4 * static_cast<std::size_t>(pool_.threads())));
  const std::size_t per_run = ceil_div(count, runs);
  std::vector<std::vector<std::uint32_t>> fresh(runs);
  pool_.run(runs, [&](std::size_t r) {
    const std::size_t a = r * per_run, b = std::min(count, a + per_run);
    prepare_run(rows, a, b, offset, out, at, fresh[r]);
  });
  begin_fresh(fresh);
}

void EvalEngine::add_window(const VectorRow* rows, std::size_t count, std::size_t offset,
                            BatchResults* out) {
  deferral_.update(lanes_, slots_.params.size());
  t_.resize(count);
  slot_.resize(count);
  reference_.resize(count);
  const RowsView view{t_.data(), slot_.data(), reference_.data()};
  const std::size_t lanes = lanes_.size();
  const std::size_t runs = runs_per_lane(count);
  if (runs == 1) {
    prepare(rows, count, offset, out);
    merge_pending();
    const std::size_t group = merge_group_size();
    pool_.run(ceil_div(lanes, group), [&](std::size_t task) {
      const std::size_t first = task * group;
      run_group(first, std::min(group, lanes - first), view, count, offset, out);
    });
    return;
  }
  // Runs of rows on every thread, each prepared and then taken through every lane in one task
  // (its rows still in the core's cache, one wait for the threads a window); the last window's
  // merges (tasks 0 .. merges - 1, one per lane, handed out first) go alongside them. A run whose
  // rows meet a slot no lane has begun waits for the slots to begin, in stream order, after the
  // others.
  auto& now = partials_[current_];
  const auto& last = partials_[1 - current_];
  for (auto& p : now) p.resize(runs);
  const std::size_t per_run = ceil_div(count, runs);
  const std::size_t merges = pending_ ? lanes : 0;
  std::vector<std::vector<std::uint32_t>> fresh(runs);
  const auto run_begin = [&](std::size_t r) { return std::min(count, r * per_run); };
  const auto run_end = [&](std::size_t r) { return std::min(count, run_begin(r) + per_run); };
  const auto run_lanes = [&](std::size_t r) {
    const std::size_t a = run_begin(r), b = run_end(r);
    for (std::size_t l = 0; l < lanes; ++l)
      lanes_[l]->accumulate(view, a, b, now[l][r], raw_at(out, l, offset),
                            skipped_at(out, l, offset));
  };
  pool_.run(merges + runs, [&](std::size_t task) {
    if (task < merges) {
      merge(last[task], task);
      return;
    }
    const std::size_t r = task - merges;
    prepare_run(rows, run_begin(r), run_end(r), offset, out, 0, fresh[r]);
    if (fresh[r].empty()) run_lanes(r);
  });
  if (begin_fresh(fresh)) {
    std::vector<std::size_t> held;
    for (std::size_t r = 0; r < runs; ++r)
      if (!fresh[r].empty()) held.push_back(r);
    pool_.run(held.size(), [&](std::size_t h) { run_lanes(held[h]); });
  }
  current_ = 1 - current_;
  pending_ = true;
}

// Lanes whose windows one task takes together (their folds side by side: merge_group), no more
// than needed to give every thread one.
std::size_t EvalEngine::merge_group_size() const {
  const std::size_t threads = static_cast<std::size_t>(pool_.threads());
  return std::min(LaneAccumulator::kMergeGroup, std::max<std::size_t>(1, lanes_.size() / threads));
}

// The window of the lanes [first, first + size): accumulated and merged at once, nothing kept.
void EvalEngine::run_group(std::size_t first, std::size_t size, const RowsView& view,
                           std::size_t count, std::size_t offset, BatchResults* out) {
  thread_local LanePartial scratch[LaneAccumulator::kMergeGroup];
  LaneAccumulator* members[LaneAccumulator::kMergeGroup];
  const LanePartial* parts[LaneAccumulator::kMergeGroup];
  TimingEngine* timing[LaneAccumulator::kMergeGroup];
  for (std::size_t j = 0; j < size; ++j) {
    const std::size_t l = first + j;
    lanes_[l]->accumulate(view, 0, count, scratch[j], raw_at(out, l, offset),
                          skipped_at(out, l, offset));
    members[j] = lanes_[l];
    parts[j] = &scratch[j];
    timing[j] = timing_[l];
  }
  LaneAccumulator::merge_group(members, parts, timing, size);
}

// Whole windows per lane on several threads: the span's windows prepared first, then each thread
// takes, until none is left that no other thread holds, the side work's next step if no thread
// has it, else the next window of the group of lanes furthest behind that no thread has. Each
// group's windows go in stream order, so its folds see the rows as one pass would.
void EvalEngine::add_span(const VectorRow* rows, std::size_t count, std::size_t offset,
                          BatchResults* out, const SideWork& side, bool& side_more) {
  const std::size_t window = options_.window_rows;
  const std::size_t windows = ceil_div(count, window);
  deferral_.update(lanes_, slots_.params.size());
  t_.resize(count);
  slot_.resize(count);
  reference_.resize(count);
  for (std::size_t w = 0; w < windows; ++w) {
    const std::size_t at = w * window;
    prepare(rows + at, std::min(window, count - at), offset + at, out, at);
  }
  const std::size_t lanes = lanes_.size();
  const std::size_t group = merge_group_size();
  const std::size_t groups = ceil_div(lanes, group);
  std::mutex mutex;
  std::vector<std::size_t> next(groups, 0);
  std::vector<std::uint8_t> busy(groups, 0);
  bool side_busy = false;
  pool_.run(static_cast<std::size_t>(pool_.threads()), [&](std::size_t) {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      if (side_more && !side_busy) {
        side_busy = true;
        lock.unlock();
        const bool more = side();
        lock.lock();
        side_busy = false;
        side_more = more;
        continue;
      }
      std::size_t g = groups;
      for (std::size_t k = 0; k < groups; ++k)
        if (!busy[k] && next[k] < windows && (g == groups || next[k] < next[g])) g = k;
      if (g == groups) return;
      busy[g] = 1;
      const std::size_t at = next[g]++ * window;
      lock.unlock();
      const RowsView view{t_.data() + at, slot_.data() + at, reference_.data() + at};
      run_group(g * group, std::min(group, lanes - g * group), view, std::min(window, count - at),
                offset + at, out);
      lock.lock();
      busy[g] = 0;
    }
  });
}

}  // namespace glint
