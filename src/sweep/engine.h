// The sweep's engine: one stream of shading requests, read once, through every configuration of a
// sweep. All configurations' accumulators stay in memory and each chunk of rows goes through all
// of them before the next is read, so memory is flat in the stream's length and many
// configurations share one reading pass.
//
// Every configuration is a lane of one evaluation engine (eval/engine.h, the engine under `glint
// eval` and `glint sim`'s fast mode): the untimed bit-accurate datapaths, the accuracy statistics
// `glint eval` reports and the timing recurrences `glint sim` runs (timing/timing.h), each
// configuration's window of rows one task, the float reference computed once for all of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "eval/activity.h"
#include "eval/engine.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "sweep/grid.h"
#include "timing/timing.h"

namespace glint {

struct SweepSettings {
  int display_bits = 8;  // errors in LSBs of this depth (--display-bits)
  Chip chip;             // --chip: the chip every configuration is built on
  EpsMeasure eps_measure = EpsMeasure::kLuminance;  // --eps-measure
  int jobs = 1;                                     // threads (results do not depend on it)
  SinkReady sink;     // sink backpressure of the timing model (default: always ready)
  bool node = false;  // --node: each row's area and critical path at the node ("node")
  // With node: each row's energy on the stream with this gating (eval/energy.h; the rows'
  // "energy_pj_per_request", sweep's energy front and size's --objective energy).
  Gating gating = Gating::kOperand;
  // Configurations per Evaluator (built on the threads by block), and rows per window of the
  // engine (each thread keeps ~16 bytes per row of it).
  std::size_t block = 64;
  std::size_t chunk_rows = 16384;
};

class SweepEngine {
 public:
  // Builds every configuration for the stream's slots on the settings' chip (make_slots,
  // specs_on_chip; SlotCapacityError when the chip is too small). A configuration the unit cannot
  // build for this stream (schlick's matched n' beyond its n register for a material's shininess,
  // ...) is refused: it runs on no row and its report row says why ("refused"), the rest of the
  // sweep goes on.
  SweepEngine(const VectorHeader& header, std::vector<SweepConfig> configs,
              const SweepSettings& settings);
  ~SweepEngine();
  SweepEngine(const SweepEngine&) = delete;
  SweepEngine& operator=(const SweepEngine&) = delete;

  // The next rows of the stream, in order, through every configuration.
  void add(const VectorRow* rows, std::size_t count);

  std::uint64_t rows() const { return rows_; }
  std::size_t size() const { return configs_.size(); }
  const std::vector<SweepConfig>& configs() const { return configs_; }
  const SlotMap& slots() const { return slots_; }

  // One report row per configuration, in the engine's order (report.h describes a row): spec,
  // cost, timing, operations, errors and digest, or only the spec and "refused". "image",
  // "error" and "pareto" are added later.
  std::vector<nlohmann::json> results() const;
  // Where add() spent its time (seconds of wall clock, over every call): the engine's (datapaths,
  // statistics and timing recurrences).
  struct Profile {
    double evaluate_s = 0;
  };
  const Profile& profile() const { return profile_; }

  // Why configuration k (in the engine's order) was refused; empty when it runs.
  const std::string& refused(std::size_t k) const { return refused_[k]; }

 private:
  struct Block;
  std::vector<SweepConfig> configs_;
  SweepSettings settings_;
  SlotMap slots_;
  std::vector<std::unique_ptr<Block>> blocks_;
  std::vector<std::string> refused_;        // per configuration: why it was refused, or empty
  std::vector<ActivityCounter*> activity_;  // with node: every block's, in the engine's order
  std::unique_ptr<EvalEngine> engine_;
  std::uint64_t rows_ = 0;
  Profile profile_;
};

}  // namespace glint
