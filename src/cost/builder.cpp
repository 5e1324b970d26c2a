#include "cost/builder.h"

#include <fmt/format.h>

#include <optional>

namespace glint {

void comparator_stage(CostBuilder& b, const LaneShape& L, bool carry_root) {
  const int wi = L.in.width();
  // Per slot: its threshold and, when slots share datapath groups, its group's id (otherwise the
  // slot id is the group id). Without the comparator only the id is left to look up.
  std::optional<Seg> tau, root;
  const int w = (L.skip ? wi : 0) + (L.slot_to_group ? L.group_bits : 0);
  if (w > 0) {
    // Read by the slot id from the lane's input port, not a register: at the node it is priced
    // as a table read by a computed address (no weak flip-flop driving its muxes).
    tau = b.slot_table(L.slots, w, 1, true,
                       !L.skip           ? "group id table (per slot)"
                       : L.slot_to_group ? "tau table (per slot, with its group id)"
                                         : "tau table (per slot)",
                       nullptr, 1, true);
    b.request_op("table_read");
  }
  // hast/horner: the u scaler's root is the datapath group's (its slots' smallest tau), not a
  // slot's threshold.
  if (carry_root) {
    root = b.slot_table(L.groups, wi, 1, true, "root table (per datapath group)", nullptr, 1, true);
    b.request_op("table_read");
  }
  std::vector<Seg> path;
  std::optional<Seg> beside_compare;
  if (tau && root && !L.slot_to_group) {
    path.push_back(parallel(*tau, *root));  // both read by the slot id
  } else {
    if (tau) path.push_back(*tau);
    beside_compare = root;  // read by the group id the tau entry gives
  }
  if (L.skip) {
    const Seg cmp = b.comparator(wi, "tau comparator");
    path.push_back(beside_compare ? parallel(*beside_compare, cmp) : cmp);
    b.request_op("compare");
  } else if (beside_compare) {
    path.push_back(*beside_compare);
  }
  // The register after the compare is the datapath's input (t and the group id, loaded by a
  // computed request: hdl/verilog.h, datapath_input_stage); the skip flag travels with the
  // bypass tag (merge_buffer) and the root is read again from the group id where it is used.
  b.reg(wi + L.group_bits, "comparator register", true);
  b.stage("comparator", path);
}

void merge_buffer(CostBuilder& b, const LaneShape& L) {
  const int w = L.out.width();
  const int tag = clog2(L.buffer), count = clog2(L.buffer + 1);
  // Entries: the result and its valid and skipped bits, written from the bypass (a 0) or the
  // datapath: an AND a bit and the entry's write decode (two tag compares).
  // Without the comparator (skip=off) nothing bypasses: Yosys removes the bypass register, the
  // skipped bits and the select, leaving the result, its valid bit and one write decode.
  const int sources = L.skip ? 2 : 1;
  b.reg(w + sources, "merge buffer", true, L.buffer);
  b.gates(L.buffer * ((L.skip ? w : 0) + sources * 2 * tag),
          "merge buffer write select and decode");
  if (L.buffer > 1) b.mux(w + sources - 1, L.buffer, "merge buffer read mux");
  // The entry's tag and a valid bit beside each of the L + 1 positions (plain flip-flops), the
  // bypass tag and valid bit.
  b.reg((L.latency + 1) * (tag + 1), "merge buffer tags beside the unit");
  if (L.skip) b.reg(tag + 1, "bypass tag", true);
  // Credits, issue and head counters (wrapping incrementers), the II counter.
  const int counters = 2 * tag + count + (L.ii > 1 ? clog2(L.ii) : 0);
  b.reg(counters, "credit, issue, head (and II) counters", true);
  b.adder(counters, "counter incrementers");
  // The head register selects the leaving entry among all B of them (a mux it drives unbuffered,
  // as a RAM's read address: its node delay grows with the B x width muxes), then the choice
  // between the entry and a result arriving at the head, to the output port.
  const NodeConstants& n = b.node();
  const Seg head_tag{"head == tag", 0, n.comparator.delay.at(tag, tag, 0)};
  if (L.buffer > 1)
    b.lane_path("merge buffer read", {{fmt::format("read mux {}x{}", L.buffer, w + sources), 0,
                                       b.select_ns(n.ram, L.buffer, w + sources)},
                                      {"arrival mux", 0, b.select_ns(n.mux, 2, w)}});
  // Writing an entry: the head's valid bit read, the retire, then the write enable of the entry's
  // w + sources flip-flops.
  b.lane_path("merge buffer write",
              {L.buffer > 1 ? Seg{"valid bit read", 0, b.select_ns(n.ram, L.buffer, 1)} : head_tag,
               {"retire to every entry's decode", 0, b.select_ns(n.mux, 2, L.buffer)},
               {"entry enable", 0, b.select_ns(n.mux, 2, w + sources)}});
}

}  // namespace glint
