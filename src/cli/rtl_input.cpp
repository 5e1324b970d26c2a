#include "cli/rtl_input.h"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "cli/cli.h"
#include "hdl/sdc.h"
#include "hdl/verilog.h"
#include "render/render.h"
#include "scene/scene.h"
#include "units/catalogue.h"

namespace glint::cli {

void add_rtl_input_options(CLI::App* sub, RtlInputOptions& o) {
  sub->add_option("--vectors", o.vectors,
                  "Vector file whose materials and lights give the slots (traces/README.md)");
  sub->add_option("--scene", o.scene, "Scene whose materials and lights give the slots");
  sub->add_option("--material", o.materials,
                  "A material as a vector file's material line after the word `material`, e.g. "
                  "'gold shininess=64 lobe=blinn specular=1,0.77,0.34' (repeatable; specular "
                  "defaults to 1,1,1, lobe to phong)");
  sub->add_option("--eps", o.eps, "Perceptibility threshold eps of --material (default 1e-3)");
  add_eps_measure_option(sub, o.eps_measure);
  add_chip_option(sub, o.chip);
}

void check_rtl_input(const RtlInputOptions& o) {
  const int given = !o.vectors.empty() + !o.scene.empty() + !o.materials.empty();
  if (given != 1)
    throw std::invalid_argument(
        "give the slots one way: --vectors FILE, --scene SCENE or --material ... (one of them)");
  if (o.materials.empty() && o.eps != 1e-3)
    throw std::invalid_argument("--eps goes with --material (files and scenes give their own)");
  require_finite_positive(o.eps, "--eps");
}

VectorHeader rtl_header(const RtlInputOptions& o) {
  if (!o.vectors.empty()) return with_eps_measure(VectorReader(o.vectors).header(), o.eps_measure);
  if (!o.scene.empty())
    return with_eps_measure(scene_request_header(load_scene(o.scene)), o.eps_measure);
  // A vector file of the materials alone: its reader checks every field and names the line
  // (line 4 is the first --material).
  std::string text = fmt::format("glint-vectors 1\neps {}\nlights 1\n", o.eps);
  for (const std::string& m : o.materials) {
    if (m.find('\n') != std::string::npos)
      throw std::invalid_argument("--material: one line per material");
    // White and Phong unless given: the colour changes only the material's c_y (its tau).
    text += "material " + m;
    if (m.find("specular=") == std::string::npos) text += " specular=1,1,1";
    if (m.find("lobe=") == std::string::npos) text += " lobe=phong";
    text += "\n";
  }
  text += "columns t material\ndata\n";
  std::istringstream in(text);
  return with_eps_measure(VectorReader(in, "--material").header(), o.eps_measure);
}

std::string rtl_input_name(const RtlInputOptions& o) {
  return !o.vectors.empty() ? o.vectors : !o.scene.empty() ? o.scene : "--material";
}

RtlDesign make_rtl_design(const UnitSpec& spec, const VectorHeader& header,
                          const std::string& input, const Chip& chip) {
  RtlDesign d;
  try {
    d.slots = make_slots(header, chip);
  } catch (const SlotCapacityError& e) {
    refuse_chip(chip, e);  // the input needs more than the chip holds
  } catch (const ResourceLimitError& e) {
    refuse_size(input, e);  // more slots or light x material pairs than a stream may have
  }
  d.unit = make_unit(specs_for_chip({spec}, chip).front(), d.slots);
  const SpecularUnit& u = *d.unit;
  hdl::LaneParams& p = d.lane;
  p.unit = u.name();
  p.spec = u.canonical_spec();
  p.generator = std::string("glint ") + GLINT_VERSION;
  p.in = u.in_format();
  p.out = u.out_format();
  p.latency = u.timing().latency;
  p.ii = u.timing().ii;
  p.buffer = u.timing().buffer_depth;
  p.comparator = u.comparator_enabled();
  p.groups = std::max(u.datapath_groups(), u.group_capacity());
  for (std::size_t s = 0; s < u.slots(); ++s) {
    p.threshold.push_back(u.tau_raw(s));
    p.group.push_back(static_cast<std::uint32_t>(u.datapath_of(s)));
    p.slot_names.push_back(s < d.slots.params.size() ? d.slots.params[s].name : "");
  }
  // A chip of given capacity: the slots the input leaves free never skip and read group 0 until
  // the driver loads them (tables=ram: every entry has the write port).
  for (std::size_t s = u.slots(); s < u.slot_capacity(); ++s) {
    p.threshold.push_back(-1);
    p.group.push_back(0);
    p.slot_names.push_back("free (loaded at run time)");
  }
  hdl::DatapathPorts ports;
  ports.module = fmt::format("glint_{}_datapath", p.unit);
  ports.in = p.in;
  ports.out = p.out;
  ports.group_bits = hdl::group_bits(p);
  ports.groups = p.groups;
  ports.latency = p.latency;
  if (!u.tables_ram()) {
    d.lane_verilog = "`timescale 1ns / 1ps\n" + hdl::lane_module(p);
    d.datapath_verilog = "`timescale 1ns / 1ps\n" + u.rtl_datapath(ports);
    return d;
  }
  // tables=ram: the write port's widths hold every table of the lane and the datapath, so the
  // lane is elaborated once to list them (selects, entries, widths), then written with them.
  p.tables_ram = true;
  hdl::RamTables listing;
  hdl::lane_module(p, &listing);
  ports.ram = &listing;
  u.rtl_datapath(ports);
  listing.size_port();
  p.ram = listing;
  hdl::RamTables ram = listing;
  ram.tables.clear();
  d.lane_verilog = "`timescale 1ns / 1ps\n" + hdl::lane_module(p, &ram);
  ports.ram = &ram;
  d.datapath_verilog = "`timescale 1ns / 1ps\n" + u.rtl_datapath(ports);
  if (ram.tables.size() != listing.tables.size())
    throw std::logic_error("rtl: the RAM tables differ between the two elaborations");
  p.ram = std::move(ram);
  return d;
}

void add_clock_period_option(CLI::App* sub, double& period_ns) {
  sub->add_option("--clock-period", period_ns,
                  fmt::format("Clock period of the lane's SDC constraints, in ns (default {:g})",
                              hdl::kDefaultClockPeriodNs))
      ->check(CLI::Range(1e-3, 1e6));
}

}  // namespace glint::cli
