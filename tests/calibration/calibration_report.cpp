// The cost proxy against Yosys on the calibration set (src/cost/README.md, "Calibration against
// Yosys"): for each stored `glint synth` result (tests/calibration/set.json, written by
// synth_set.py) the lane is built again for the same spec and vector file, its proxy computed
// (units/lane_cost.h), and a markdown table printed: proxy GE, Yosys GE, their ratio, the proxy's
// critical path and the synthesized depth of the slowest stage. No Yosys run: it reads what is
// stored.
//
//   calibration_report SET_JSON [--check [MIN]]
//
// --check (the ctests `calibration` and `calibration_holdout`) exits 1 unless the targets of
// issue 10 hold: at least MIN configurations (default 30), every area within +-10 % of Yosys' GE,
// Spearman rank correlation of the areas >= 0.98, every critical path within +-20 % of the
// synthesized depth.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace {

// Ranks with ties averaged.
std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> idx(v.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < idx.size();) {
    std::size_t j = i;
    while (j + 1 < idx.size() && v[idx[j + 1]] == v[idx[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[idx[k]] = (static_cast<double>(i + j) / 2.0) + 1.0;
    i = j + 1;
  }
  return r;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const std::vector<double> ra = ranks(a), rb = ranks(b);
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / n;
  const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - ma) * (rb[i] - mb);
    saa += (ra[i] - ma) * (ra[i] - ma);
    sbb += (rb[i] - mb) * (rb[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: calibration_report SET_JSON [--check [MIN]]\n");
    return 2;
  }
  const bool check = argc > 2 && std::string(argv[2]) == "--check";
  const std::size_t min_configs = argc > 3 ? std::stoul(argv[3]) : 30;
  const std::string set_path = argv[1];
  // The vector files' paths are relative to the repository (set.json is in tests/calibration/).
  const std::string root = set_path.substr(0, set_path.rfind('/') + 1) + "../../";
  std::ifstream in(set_path);
  if (!in) {
    std::fprintf(stderr, "calibration_report: cannot read %s\n", set_path.c_str());
    return 2;
  }
  const nlohmann::json set = nlohmann::json::parse(in);
  std::vector<double> proxy, yosys;
  int area_misses = 0, delay_misses = 0;
  double worst_area = 0, worst_delay = 0;
  std::cout << "| config | proxy GE | Yosys GE | ratio | proxy delay | Yosys depth | ratio |\n"
               "|---|---|---|---|---|---|---|\n";
  for (const auto& c : set.at("configs")) {
    const std::string spec = c.at("spec").get<std::string>();
    const std::string vectors = c.at("vectors").get<std::string>();
    const glint::VectorHeader header = glint::VectorReader(root + vectors).header();
    const glint::SlotMap slots = glint::make_slots(header);
    const auto unit = glint::make_unit(glint::parse_unit_spec(spec), slots);
    const glint::UnitCost cost = glint::unit_cost(*unit);
    const double ge = c.at("ge").get<double>();
    const double depth = c.at("depth").get<double>();
    const double ra = cost.area_ge / ge, rd = cost.critical_path / depth;
    proxy.push_back(cost.area_ge);
    yosys.push_back(ge);
    const bool area_ok = std::abs(ra - 1) <= 0.10, delay_ok = std::abs(rd - 1) <= 0.20;
    area_misses += !area_ok;
    delay_misses += !delay_ok;
    worst_area = std::max(worst_area, std::abs(ra - 1));
    worst_delay = std::max(worst_delay, std::abs(rd - 1));
    const std::string file = vectors.substr(vectors.rfind('/') + 1);
    std::cout << fmt::format(
        "| `{}` {} | {:.0f} | {:.0f} | {:.2f}{} | {:.0f} | {:.0f} | {:.2f}{} |\n", spec, file,
        cost.area_ge, ge, ra, area_ok ? "" : " **", cost.critical_path, depth, rd,
        delay_ok ? "" : " **");
  }
  const double rho = spearman(proxy, yosys);
  std::cout << fmt::format(
      "\n{} configurations: area within +-10 % for {} (worst {:.1f} %), Spearman {:.3f}; critical "
      "path within +-20 % for {} (worst {:.1f} %)\n",
      proxy.size(), proxy.size() - static_cast<std::size_t>(area_misses), 100 * worst_area, rho,
      proxy.size() - static_cast<std::size_t>(delay_misses), 100 * worst_delay);
  if (!check) return 0;
  const bool ok =
      proxy.size() >= min_configs && area_misses == 0 && rho >= 0.98 && delay_misses == 0;
  std::cout << (ok ? "PASS: calibration targets hold\n" : "FAIL: calibration targets missed\n");
  return ok ? 0 : 1;
}
