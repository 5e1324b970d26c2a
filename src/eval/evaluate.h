// Untimed evaluation of units over a vector stream: slots from the header, the float reference per
// request, and the statistics every report carries (the model error and the datapath error kept
// apart, as the accuracy contract asks).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/vectors.h"
#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {

// How the stream's materials (and lights) map to unit slots.
struct SlotMap {
  std::vector<MaterialParams> params;  // one per slot
  std::vector<Lobe> lobe;              // lobe of each slot's material
  std::vector<double> roughness;       // gaussian omega (0 otherwise)
  std::vector<double> c_y;             // luminance behind each slot's tau
  bool per_light = false;              // slots are light x material (coloured lights)
  std::size_t materials = 0;

  std::size_t slot(const VectorRow& row) const {
    return per_light ? static_cast<std::size_t>(row.light) * materials + row.material
                     : row.material;
  }
};

// Per material (Källberg eq.6) when every light is white, else per light x material (eq.3);
// eps is divided by the light count (Källberg §2, eps_n = eps/n).
SlotMap make_slots(const VectorHeader& header);

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

struct UnitStats {
  std::string name, spec;
  nlohmann::json description;
  std::uint64_t vectors = 0, skipped = 0;
  ErrorStats total;     // fixed result vs float reference (what a user sees)
  ErrorStats model;     // unit's float approximation vs float reference (model error)
  double max_ulps = 0;  // fixed result vs the unit's own real model, in output ulps
  double t_at_max_ulps = 0;
  std::uint64_t mismatch8 = 0;  // round(255 x) differs from the float reference's
  double error_bound = 0;       // largest stated bound over slots (pow, lut); NaN otherwise

  nlohmann::json to_json() const;
};

// Accuracy statistics of one lane (a unit), fed one result at a time: by `glint eval`, by the fast
// mode's batch loop and by the clocked mode's scoreboard. One accumulation for every path.
// The float reference of one request, computed once and shared by every lane.
struct RowReference {
  double t = 0;
  double value = 0;  // reference_value(): max(0,t)^n or the Gaussian lobe
  long value8 = 0;   // round(255 * value): the 8-bit display code
};
RowReference make_reference(const SlotMap& slots, std::size_t slot, double t);

class LaneAccumulator {
 public:
  explicit LaneAccumulator(const SpecularUnit& unit);

  void add(std::size_t slot, const RowReference& ref, std::int64_t t_raw, bool skipped,
           std::int64_t out_raw);
  // A digest of every (skipped, out_raw) in stream order: bit-accurate regression in 64 bits.
  std::uint64_t digest() const { return digest_; }
  const UnitStats& stats() const { return stats_; }
  UnitStats& stats() { return stats_; }

 private:
  double model(std::size_t slot, std::int64_t t_raw);

  const SpecularUnit& unit_;
  UnitStats stats_;
  std::uint64_t digest_ = 0xcbf29ce484222325ULL;
  double ulp_ = 0, out_scale_ = 0;
  // The unit's real-valued model per (slot, input raw), memoised when the input is <= 20 bits:
  // a long stream revisits the same 2^16 inputs, and the model is the costly part of the check.
  std::vector<std::vector<double>> memo_;
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

// Schema version of the `glint eval` JSON report (key "glint_eval_report", schema in README.md).
// Version 1 is the unversioned layout before eval took `glint sim`'s key names (error_vs_reference,
// datapath_error_ulps, top-level mismatch_8bit_fraction and error_bound); 2 nests them in "errors".
inline constexpr int kEvalReportVersion = 2;

class Evaluator {
 public:
  Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs);

  void add(const VectorRow& row, const std::function<void(const EvalRecord&)>& dump = {});
  std::vector<UnitStats> stats() const;
  const std::string& label(std::size_t unit) const { return lanes_[unit].stats().name; }
  const std::vector<std::unique_ptr<SpecularUnit>>& units() const { return units_; }
  const SlotMap& slots() const { return slots_; }
  // The report's version, slots and units (the caller adds vectors_file and rows).
  nlohmann::json to_json() const;

 private:
  SlotMap slots_;
  std::vector<std::unique_ptr<SpecularUnit>> units_;
  std::vector<LaneAccumulator> lanes_;
};

// The summary table printed by `glint eval`.
std::string format_eval_table(const std::vector<UnitStats>& stats);

}  // namespace glint
