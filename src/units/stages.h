// The pipeline of a unit as its registers: which stage holds which named values after each clock,
// at which widths and formats. One layout per unit, used by the staged evaluation (the datapath's
// register values, request by request), the SystemC model (what each stage traces) and the tests
// that read the VCD back.
//
// Every stage also carries the request's t and its stream index (the SystemC model traces both in
// every stage); the layout lists what each stage adds.
//
// Positions: 0 is the compute path's input register ("in": t as the comparator passed it), 1..L
// the unit's stages, L = timing latency; the last stage's last register is the result. A stage
// may span several positions (an iterative block that keeps one request for several cycles, e.g.
// the radix-2 divider loop): its registers then hold the values of the iteration the request is
// in, one set per position.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fixed_point.h"

namespace glint {

struct StageRegister {
  std::string name;  // e.g. "u", "acc", "remainder"
  QFormat format;    // width, fraction bits and signedness of the raw value
};

struct Stage {
  std::string name;  // e.g. "scale", "mac1", "q0", "div", "round"
  int first = 0;     // positions [first, last]
  int last = 0;
  std::vector<StageRegister> registers;
};

// The stages of one unit, checked: they cover positions 0..L contiguously, names are unique and
// usable as VCD scope names, a stage spanning k > 1 positions needs II >= k (it holds one request
// for k cycles), and the last stage ends with its result register in the output format.
class StageLayout {
 public:
  StageLayout() = default;
  // Throws std::invalid_argument naming what is wrong.
  StageLayout(std::vector<Stage> stages, int ii, const QFormat& out);

  const std::vector<Stage>& stages() const { return stages_; }
  int latency() const { return static_cast<int>(stage_of_.size()) - 1; }
  // The stage holding position p (0..L).
  const Stage& stage_at(int position) const { return stages_[stage_of_[position]]; }
  std::size_t stage_index_at(int position) const { return stage_of_[position]; }
  // Staged values: the registers of positions 1..L in order, position p's from offset(p).
  std::size_t offset(int position) const { return offset_[position]; }
  std::size_t size() const { return offset_.back(); }
  // Flat index of the result register (the last value of position L).
  std::size_t result_index() const { return size() - 1; }

 private:
  std::vector<Stage> stages_;
  std::vector<std::size_t> stage_of_;  // per position
  std::vector<std::size_t> offset_;    // per position 0..L, plus the end
};

// The compute input stage every unit starts with (it holds t only, which every stage carries).
Stage input_stage();

// Where a datapath's staged evaluation writes: StageProbe records each (position, register) value
// into a flat array laid out by a StageLayout; NoProbe is the fast path, which the compiler removes
// entirely (kActive lets a datapath skip work done only to show intermediate values).
struct NoProbe {
  static constexpr bool kActive = false;
  void operator()(int /*position*/, int /*reg*/, std::int64_t /*value*/) const {}
};

class StageProbe {
 public:
  static constexpr bool kActive = true;
  StageProbe(const StageLayout& layout, std::int64_t* values) : layout_(layout), values_(values) {}
  void operator()(int position, int reg, std::int64_t value) const {
    values_[layout_.offset(position) + static_cast<std::size_t>(reg)] = value;
  }

 private:
  const StageLayout& layout_;
  std::int64_t* values_;
};

}  // namespace glint
