// A program that uses all of glint, the SystemC model included (glint::glint / glint.pc).
// libsystemc defines main() and calls sc_main(), so this program starts here (a program may instead
// define its own main(), which takes precedence, and an sc_main for the linker, as src/cli/main.cpp
// does). It runs a short stream through the fast-mode model and checks every result against the
// untimed datapath.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <systemc>
#include <vector>

#include "rtl_model/fast_sim.h"

int sc_main(int, char*[]) {
  glint::VectorHeader header;
  header.eps = 1e-3;
  header.lights = 1;
  header.materials.push_back({"white", {1, 1, 1}, 50, glint::Lobe::kBlinn, 0});
  const glint::SlotMap slots = glint::make_slots(header);
  const std::unique_ptr<glint::SpecularUnit> unit =
      glint::make_unit(glint::parse_unit_spec("hast"), slots);

  const std::vector<double> ts{1.0, 0.5, 0.95, -0.25, 0.9};
  std::size_t next = 0, matched = 0, computed = 0;
  const std::vector<glint::TimingStats> stats = glint::run_fast(
      {unit.get()}, slots,
      [&](glint::VectorRow& row) {
        if (next == ts.size()) return false;
        row = glint::VectorRow{};
        row.t = ts[next];
        row.line = ++next;
        return true;
      },
      glint::FastOptions{}, nullptr,
      [&](const glint::FastResult& r) {
        const std::int64_t want =
            unit->eval_with_skip(0, glint::quantize_input(r.row->t, unit->in_format()));
        if (r.out_raw == want) ++matched;
        if (!r.skipped) ++computed;
      });
  const bool ok =
      stats.size() == 1 && stats[0].results == ts.size() && matched == ts.size() && computed == 3;
  std::printf(
      "glint sc consumer: %llu results, %zu computed, %zu match the datapath, %llu cycles: %s\n",
      static_cast<unsigned long long>(stats.at(0).results), computed, matched,
      static_cast<unsigned long long>(stats.at(0).cycles), ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
