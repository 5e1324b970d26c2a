#include "units/stage_rtl.h"

#include <fmt/format.h>

#include <stdexcept>

#include "hdl/verilog.h"

namespace glint {

std::string rtl_reg(const Stage& s, std::size_t r) {
  return s.name + "_" + s.registers.at(r).name;
}

std::string rtl_stage_registers(const Stage& s, const std::string& what) {
  const std::string where = s.first == s.last ? fmt::format("position {}", s.first)
                                              : fmt::format("positions {}..{}", s.first, s.last);
  std::string out = "\n" + hdl::comment(fmt::format("---- {}, stage {}: {}", where, s.name, what));
  for (std::size_t r = 0; r < s.registers.size(); ++r) {
    const QFormat& f = s.registers[r].format;
    out += fmt::format("  reg {}{} {};  // {}\n", f.is_signed ? "signed " : "",
                       hdl::range(f.width()), rtl_reg(s, r), hdl::describe(f));
  }
  return out;
}

const Stage& rtl_stage(const StageLayout& layout, const std::string& name) {
  for (const Stage& s : layout.stages())
    if (s.name == name) return s;
  // not from a spec: a generator out of step with its unit's layout
  throw std::logic_error("rtl: no stage '" + name + "' in the unit's layout");
}

}  // namespace glint
