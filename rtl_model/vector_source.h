// VectorSource: the head of a lane. Pulls rows from its RowStream and presents one request at a
// time in its output register (valid, t_raw in the unit's input format, slot, stream index); the
// register advances at an edge where valid && ready (the comparator takes the request). It always
// has the next request ready (src/timing.h: "the source always has the next request ready"): the
// row after the presented one is read ahead, which is also how it knows the `last` flag.
//
// t_raw comes from the datapath's front end (InputQuantizer: quantize_input with its format's
// checks and scale worked out once) and the slot from SlotMap::slot; the module adds nothing of its
// own. The rows themselves stay in a RowRing until the scoreboard retires them (testbench sideband,
// so the result callback can name its row).
#pragma once

#include <cstdint>
#include <string>
#include <systemc>
#include <vector>

#include "eval/evaluate.h"
#include "rtl_model/row_stream.h"
#include "rtl_model/rtl_common.h"
#include "rtl_model/sim_control.h"
#include "units/catalogue.h"
#include "units/common.h"

namespace glint::rtl {

// Rows in flight, indexed by stream index modulo its size. With B merge-buffer credits at most B
// requests are issued and not retired, plus the one presented: B + 2 entries never collide. The
// size is rounded up to a power of two, so the index is a mask, not a division per row.
class RowRing {
 public:
  explicit RowRing(std::size_t size) : rows_(round_up(size)), mask_(rows_.size() - 1) {}
  VectorRow& at(std::uint64_t seq) { return rows_[static_cast<std::size_t>(seq & mask_)]; }
  const VectorRow& at(std::uint64_t seq) const {
    return rows_[static_cast<std::size_t>(seq & mask_)];
  }
  std::size_t size() const { return rows_.size(); }

 private:
  static std::size_t round_up(std::size_t n) {
    std::size_t p = 1;
    while (p < n) p *= 2;
    return p;
  }
  std::vector<VectorRow> rows_;
  std::uint64_t mask_;
};

class VectorSource : public sc_core::sc_module, public Traceable, public ClockedStage {
 public:
  In<bool> ready;  // from the comparator

  Register<bool> valid;
  Register<Request> request;

  // Reads the first rows now (elaboration), so a malformed stream fails before simulation.
  VectorSource(sc_core::sc_module_name name, RowStream& stream, const SpecularUnit& unit,
               const SlotMap& slots, RowRing& ring, SimControl& control, bool tracing);

  // Rows presented so far (the stream's length once it is drained).
  std::uint64_t presented() const { return presented_; }
  bool empty() const { return presented_ == 0; }

  void add_traces(VcdWriter& vcd, const std::string& prefix) const override;
  void tick() override;

 private:
  void load();  // presents the read-ahead row (or drops valid at the end) and reads the next one

  RowStream& stream_;
  const SpecularUnit& unit_;
  const SlotMap& slots_;
  RowRing& ring_;
  SimControl& control_;
  const bool tracing_;
  const InputQuantizer quantize_;
  const std::size_t unit_slots_;

  VectorRow ahead_;
  bool have_ahead_ = false;
  bool valid_ = false;
  std::uint64_t presented_ = 0;

  RawBits t_trace_, slot_trace_, seq_trace_;
};

}  // namespace glint::rtl
