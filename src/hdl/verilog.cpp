#include "hdl/verilog.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace glint::hdl {

int index_bits(std::uint64_t n) {
  int b = 1;
  while (b < 64 && (std::uint64_t{1} << b) < n) ++b;
  return b;
}

int value_bits(std::uint64_t v) {
  int b = 1;
  while (b < 64 && (v >> b) != 0) ++b;
  return b;
}

namespace {
// The two's-complement bits of v in `width` bits (1..127: products of the wide datapaths exceed
// 64), as hexadecimal digits, or nothing when they are 0..9 (written in decimal).
std::string hex_bits(int width, std::int64_t v, unsigned& small) {
  if (width < 1 || width > 127) throw std::invalid_argument(fmt::format("hdl: width {}", width));
  const unsigned __int128 mask = (static_cast<unsigned __int128>(1) << width) - 1;
  unsigned __int128 b = static_cast<unsigned __int128>(static_cast<__int128>(v)) & mask;
  if (b <= 9) {
    small = static_cast<unsigned>(b);
    return "";
  }
  std::string digits;
  while (b != 0) {
    digits.insert(digits.begin(), "0123456789abcdef"[static_cast<unsigned>(b & 15)]);
    b >>= 4;
  }
  return digits;
}
}  // namespace

std::string lit(int width, std::int64_t v) {
  unsigned small = 0;
  const std::string h = hex_bits(width, v, small);
  return h.empty() ? fmt::format("{}'d{}", width, small) : fmt::format("{}'h{}", width, h);
}

std::string slit(int width, std::int64_t v) {
  unsigned small = 0;
  const std::string h = hex_bits(width, v, small);
  return h.empty() ? fmt::format("{}'sd{}", width, small) : fmt::format("{}'sh{}", width, h);
}

std::string range(int width) {
  return fmt::format("[{}:0]", width - 1);
}

std::string describe(const QFormat& f) {
  return fmt::format("{} ({} bits, {} fraction{})", f.name(), f.width(), f.frac_bits,
                     f.is_signed ? ", two's complement" : "");
}

std::string comment(const std::string& text, int indent) {
  std::string out;
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    const std::string line =
        text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    out += pad + (line.empty() ? "//" : "// " + line) + "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

namespace {

// The comment, the declaration line(s) `head` and the case statement on `selector`; `tail`
// closes the block.
std::string rom_text(const Rom& r, const std::string& head, const std::string& selector,
                     const std::string& tail) {
  if (r.words.size() > (std::uint64_t{1} << r.addr_bits) || r.words.empty())
    throw std::invalid_argument(fmt::format("hdl: ROM {}: {} words for {} address bits", r.name,
                                            r.words.size(), r.addr_bits));
  std::string s;
  if (!r.comment.empty()) s += comment(r.comment);
  s += head;
  s += fmt::format("    case ({})\n", selector);
  for (std::size_t i = 0; i < r.words.size(); ++i)
    s += fmt::format("      {}: {} = {};\n", lit(r.addr_bits, static_cast<std::int64_t>(i)), r.name,
                     lit(r.data_bits, r.words[i]));
  // Addresses past the contents (a ROM need not fill its address space) read `fill`.
  if (r.words.size() < (std::uint64_t{1} << r.addr_bits))
    s += fmt::format("      default: {} = {};\n", r.name, lit(r.data_bits, r.fill));
  s += "    endcase\n" + tail;
  return s;
}

}  // namespace

std::string rom(const Rom& r) {
  return rom_text(r,
                  fmt::format("  reg {}{} {};\n  always @* begin\n", r.is_signed ? "signed " : "",
                              range(r.data_bits), r.name),
                  r.addr, "  end\n");
}

std::string group_table(const std::string& name, const std::string& addr, int addr_bits, int width,
                        const std::vector<std::int64_t>& values, const std::string& what,
                        bool is_signed) {
  bool same = true;
  for (std::int64_t v : values) same = same && v == values.front();
  if (same)
    return fmt::format("  wire {}{} {} = {};  // {} (every group)\n", is_signed ? "signed " : "",
                       range(width), name,
                       is_signed ? slit(width, values.front()) : lit(width, values.front()), what);
  Rom r;
  r.name = name;
  r.addr = addr;
  r.addr_bits = addr_bits;
  r.data_bits = width;
  r.is_signed = is_signed;
  r.words = values;
  r.comment = what + " per datapath group";
  return rom(r);
}

void RamTables::size_port() {
  sel_bits = index_bits(tables.size());
  addr_bits = 1;
  data_bits = 1;
  for (const RamTable& t : tables) {
    addr_bits = std::max(addr_bits, index_bits(t.words.size()));
    data_bits = std::max(data_bits, t.width);
  }
}

std::string ram_array(RamTables& tables, RamTable t) {
  if (t.words.empty() || t.width < 1)
    throw std::invalid_argument(fmt::format("hdl: RAM table {}: no entries", t.name));
  t.select = tables.next_select();
  const int ab = index_bits(t.words.size());
  std::string s = comment(fmt::format(
      "{}\n"
      "tables=ram: {} x {} bits, written through cfg_* with cfg_sel = {} (no reset: loaded)",
      t.what, t.words.size(), t.width, t.select));
  const std::string cell = t.words.size() == 1 ? t.name + "_mem[0]"
                                               : fmt::format("{}_mem[{}]", t.name,
                                                             ext("cfg_addr", tables.addr_bits, ab));
  s += fmt::format("  reg {}{} {}_mem [0:{}];\n", t.is_signed ? "signed " : "", range(t.width),
                   t.name, t.words.size() - 1);
  s +=
      fmt::format("  always @(posedge clk) if (cfg_we && cfg_sel == {}) {} <= {};\n",
                  lit(tables.sel_bits, t.select), cell, ext("cfg_data", tables.data_bits, t.width));
  tables.tables.push_back(std::move(t));
  return s;
}

std::string ram_table(RamTables& tables, RamTable t, const std::string& addr, int addr_bits) {
  const std::string name = t.name, sign = t.is_signed ? "signed " : "";
  const int width = t.width;
  const std::size_t entries = t.words.size();
  std::string s = ram_array(tables, std::move(t));
  if (entries == 1)
    return s + fmt::format("  wire {}{} {} = {}_mem[0];\n", sign, range(width), name, name);
  return s + fmt::format("  wire {}{} {} = {}_mem[{}];\n", sign, range(width), name, name,
                         ext(addr, addr_bits, index_bits(entries)));
}

std::string ram_ports(const RamTables& tables) {
  return fmt::format(
      "\n  input  wire cfg_we,  // tables=ram: write cfg_data into entry cfg_addr of table "
      "cfg_sel\n"
      "  input  wire {} cfg_sel,\n  input  wire {} cfg_addr,\n  input  wire {} cfg_data",
      range(tables.sel_bits), range(tables.addr_bits), range(tables.data_bits));
}

std::string group_table(const DatapathPorts& p, const std::string& name, const std::string& addr,
                        int width, const std::vector<std::int64_t>& values, const std::string& what,
                        bool is_signed) {
  if (p.ram == nullptr)
    return group_table(name, addr, p.group_bits, width, values, what, is_signed);
  RamTable t;
  t.name = name;
  t.width = width;
  t.is_signed = is_signed;
  t.words = values;
  t.what = what + " per datapath group";
  return ram_table(*p.ram, std::move(t), addr, p.group_bits);
}

std::string ext(const std::string& name, int from, int to, bool is_signed) {
  if (to == from) return name;
  if (to < from) return fmt::format("{}[{}:0]", name, to - 1);
  if (is_signed) return fmt::format("{{{{{}{{{}[{}]}}}}, {}}}", to - from, name, from - 1, name);
  return fmt::format("{{{}'d0, {}}}", to - from, name);
}

std::string datapath_input_stage(const DatapathPorts& p) {
  std::string s = comment(
      "---- position 0, in: the compute path's comparator register (t and its "
      "datapath group)");
  s += fmt::format("  reg {} in_t;\n", range(p.in.width()));
  if (p.groups > 1) {
    s += fmt::format("  reg {} in_group;\n", range(p.group_bits));
    s += "  always @(posedge clk) if (start) begin\n";
    s += "    in_t <= start_t;\n    in_group <= start_group;\n  end\n";
  } else {
    s += "  wire [0:0] in_group = 1'b0;  // one datapath group\n";
    s += "  wire unused_group = ^{start_group, in_group};  // (a unit may not read it)\n";
    s += "  always @(posedge clk) if (start) in_t <= start_t;\n";
  }
  return s;
}

std::string datapath_header(const DatapathPorts& p, const std::string& header_comment) {
  std::string s = comment(header_comment, 0);
  s += fmt::format("module {} (\n", p.module);
  s += "  input  wire clk,\n";
  s += "  input  wire start,  // a computed request issues at this edge: load position 0\n";
  s += fmt::format("  input  wire {} start_t,  // t, {}\n", range(p.in.width()), describe(p.in));
  s += fmt::format("  input  wire {} start_group,  // the request's datapath group\n",
                   range(p.group_bits));
  s += fmt::format("  output wire {} result{}  // position {} (L): {}", range(p.out.width()),
                   p.ram != nullptr ? "," : "", p.latency, describe(p.out));
  if (p.ram != nullptr) s += ram_ports(*p.ram);
  s += "\n);\n";
  // The write port reaches every table of the lane; a module uses the bits its tables need.
  if (p.ram != nullptr) s += "  wire unused_cfg = ^{cfg_sel, cfg_addr, cfg_data};\n";
  return s;
}

std::string datapath_footer(const DatapathPorts& p) {
  return fmt::format("endmodule  // {}\n", p.module);
}

}  // namespace glint::hdl
