// pwp's domain=log as the kind lays it out (stage layout, cost inventory, description); pwp.cpp
// dispatches to these when the config says domain=log. The datapath: units/pwp/log_datapath.h.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "units/pwp/datapath.h"
#include "units/pwp/rtl.h"
#include "units/stages.h"

namespace glint {

class CostBuilder;
struct LaneShape;

// Column j of a shared table (lg or ex, `stride` words a segment) as a bank: its words and the
// width that holds them (two's complement when one is negative).
PwpBank pwp_log_bank(const std::vector<std::int64_t>& table, std::size_t stride, int j);

// The registers' formats (log_datapath.h's positions).
struct PwpLogFormats {
  QFormat big_e, lg_index, lg_x, lg_acc, log2t, y, y_int, ex_index, ex_x, ex_acc;
};
PwpLogFormats pwp_log_formats(const PwpConfig& c, const PwpLogTables& t);

std::vector<Stage> pwp_log_stages(const PwpConfig& c, const std::vector<PwpUnit>& units);
void pwp_log_cost(CostBuilder& b, const LaneShape& L, const PwpConfig& c,
                  const std::vector<PwpUnit>& units);
nlohmann::json pwp_log_describe(const PwpUnit& u);
// The Verilog (log_rtl.cpp).
std::string pwp_log_rtl(const hdl::DatapathPorts& p, const PwpConfig& c,
                        const std::vector<PwpUnit>& groups, const StageLayout& layout);

}  // namespace glint
