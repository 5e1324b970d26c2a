#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "eval/parallel.h"
#include "io/output_set.h"
#include "render/render.h"
#include "units/catalogue.h"
#include "units/key_table.h"

namespace glint {
namespace {

// JSON has no infinity: an image equal to the reference has no finite PSNR (null).
nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

double fraction(std::uint64_t part, std::uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

nlohmann::json reproduces_json(const RenderResult& r) {
  if (!r.reproduces) return nullptr;
  const std::optional<double> glint = r.reproduced_value();
  const bool number = !r.reproduces->quantity.empty();
  return {{"paper", r.reproduces->paper},
          {"figure", r.reproduces->figure},
          {"quantity", number ? nlohmann::json(r.reproduces->quantity) : nlohmann::json(nullptr)},
          {"paper_value", number ? nlohmann::json(r.reproduces->value) : nlohmann::json(nullptr)},
          {"glint_value", glint ? nlohmann::json(*glint) : nlohmann::json(nullptr)}};
}

// The float images written beside the PNGs (--float), or null.
nlohmann::json float_images_json(const RenderResult& r) {
  if (!r.float_format) return nullptr;
  std::vector<std::string> labels;
  for (const UnitRender& u : r.units) labels.push_back(u.label);
  return {{"format", to_string(*r.float_format)},
          {"encoding", "linear"},
          {"files", render_float_file_names(labels, *r.float_format)}};
}

// The lane without its skip beside the lane (UnitRender::WithoutSkip): what the skip buys is a
// fair figure only at equal error, so the report states that lane's error as the lane's own.
nlohmann::json without_skip_json(const UnitRender& u) {
  const UnitRender::WithoutSkip& w = *u.without_skip;
  return {{"spec", w.spec},
          {"image_error", w.error.to_json()},
          {"errors", w.stats.errors_json()},
          {"equal_error", w.error.max_lsb == u.error.max_lsb},
          {"pixels_differing", w.pixels_differing},
          {"max_lsb_between", w.max_lsb_between}};
}

}  // namespace

nlohmann::json ImageError::to_json() const {
  return {{"max_lsb", max_lsb},
          {"mean_lsb", mean_lsb},
          {"psnr_db", finite_or_null(psnr_db)},
          {"differing_fraction", differing_fraction},
          {"highlight_pixels", highlight_pixels},
          {"highlight_ratio", finite_or_null(highlight_ratio)},
          {"core_pixels", core_pixels},
          {"core_ratio", finite_or_null(core_ratio)}};
}

void SkipCounts::add(const SkipCounts& o) {
  facing_away += o.facing_away;
  zero += o.zero;
  tau += o.tau;
  computed += o.computed;
}

nlohmann::json SkipCounts::to_json() const {
  const std::uint64_t n = total();
  return {{"lit_pairs", n},
          {"facing_away", facing_away},
          {"t_le_0", zero},
          {"tau_only", tau},
          {"computed", computed},
          {"skipped_fraction_t_le_0", fraction(facing_away + zero, n)},
          {"skipped_fraction_tau", fraction(facing_away + zero + tau, n)}};
}

std::vector<std::string> RenderResult::t_inputs() const {
  // Phong lobes are fed r.v, Blinn and Gaussian ones n.h: the front end builds only what is used.
  std::vector<std::string> t;
  if (std::find(lobes.begin(), lobes.end(), "phong") != lobes.end()) t.push_back("r.v");
  if (std::find_if(lobes.begin(), lobes.end(), [](const std::string& l) { return l != "phong"; }) !=
      lobes.end())
    t.push_back("n.h");
  return t;
}

SkipCounts RenderResult::skip_total() const {
  SkipCounts t;
  for (const auto& per_light : skips)
    for (const SkipCounts& c : per_light) t.add(c);
  return t;
}

double RenderResult::unit_skipped_fraction(const UnitRender& unit) const {
  const SkipCounts total = skip_total();
  return fraction(total.facing_away + unit.skipped, total.total());
}

const char* to_string(HeatScale s) {
  return s == HeatScale::kShared ? "shared" : "own";
}

std::vector<std::string> render_file_stems(const std::vector<std::string>& labels) {
  std::vector<std::string> stems;
  for (const std::string& label : labels) {
    std::string stem;
    for (const char c : label) {
      const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                        (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '=' || c == '-';
      stem += c == ' ' ? '_' : safe ? c : '-';
    }
    stems.push_back(stem);
  }
  // Unique whatever the labels: a repeated stem gets ".2", ".3", ... after its first.
  for (std::size_t i = 0; i < stems.size(); ++i) {
    int k = 1;
    for (std::size_t j = 0; j < i; ++j)
      if (stems[j] == stems[i] || stems[j] == stems[i] + "." + std::to_string(k)) ++k;
    if (k > 1) stems[i] += "." + std::to_string(k);
  }
  return stems;
}

std::vector<std::string> render_file_names(const std::vector<std::string>& labels,
                                           const std::vector<std::string>& lights) {
  std::vector<std::string> names{"reference.png", "reference_specular.png", "skip_mask.png"};
  const std::vector<std::string> light_stems = render_file_stems(lights);
  for (std::size_t l = 0; l < std::min(lights.size(), kMaxLightSkipMasks); ++l)
    names.push_back("skip_mask_" + light_stems[l] + ".png");
  names.push_back("skip_only.png");
  for (const std::string& stem : render_file_stems(labels)) {
    names.push_back(stem + ".png");
    names.push_back(stem + "_specular.png");
    names.push_back(stem + "_error.png");
  }
  names.push_back("legend.png");
  names.push_back("contact_sheet.png");
  names.push_back("report.json");
  return names;
}

std::vector<std::string> render_float_file_names(const std::vector<std::string>& labels,
                                                 FloatFormat format) {
  const std::string ext = "." + to_string(format);
  std::vector<std::string> names{"reference" + ext, "reference_specular" + ext};
  for (const std::string& stem : render_file_stems(labels))
    names.push_back(stem + "_specular" + ext);
  return names;
}

std::vector<std::string> render_file_names(const RenderResult& r) {
  std::vector<std::string> labels;
  for (const UnitRender& u : r.units) labels.push_back(u.label);
  return render_file_names(labels, r.lights);
}

std::vector<std::string> render_unit_labels(const std::vector<UnitSpec>& given) {
  std::vector<UnitSpec> specs = given;
  if (specs.empty())
    for (const std::string& name : default_unit_names()) specs.push_back(UnitSpec{name, {}});
  // unit_info refuses an unknown name: a label becomes a file name, so only the catalogue's.
  for (UnitSpec& s : specs) s.name = unit_info(s.name).name;
  // A key's value in a spec: as given, else the catalogue's default.
  const auto value = [](const UnitSpec& spec, const std::string& key) {
    for (const auto& [k, v] : spec.keys)
      if (k == key) return v;
    for (const UnitKey& k : unit_info(spec.name).keys)
      if (k.key == key) return k.default_value;
    return std::string();
  };
  std::vector<std::string> labels;
  for (const UnitSpec& spec : specs) {
    std::vector<const UnitSpec*> same;
    std::vector<std::string> keys;
    for (const UnitSpec& other : specs) {
      if (other.name != spec.name) continue;
      same.push_back(&other);
      for (const auto& kv : other.keys)
        if (std::find(keys.begin(), keys.end(), kv.first) == keys.end()) keys.push_back(kv.first);
    }
    std::string label = spec.name;
    for (const std::string& key : keys) {
      const std::string v = value(spec, key);
      if (std::any_of(same.begin(), same.end(),
                      [&](const UnitSpec* o) { return value(*o, key) != v; }))
        label += " " + key + "=" + v;
    }
    labels.push_back(label);
  }
  // Units whose keys do not tell them apart (the same spec twice) keep name.1, name.2, ...
  return unit_labels(labels);
}

std::optional<double> RenderResult::reproduced_value() const {
  if (!reproduces || reproduces->quantity.empty()) return std::nullopt;
  if (reproduces->quantity == "tau") {
    if (slots.size() != 1) return std::nullopt;
    return slots[0]["tau"].get<double>();
  }
  const SkipCounts total = skip_total();
  return fraction(total.facing_away + total.zero + total.tau, total.total());
}

std::string reproduces_line(const RenderResult& r) {
  if (!r.reproduces) return "";
  const SceneReproduces& p = *r.reproduces;
  if (p.quantity.empty())
    return fmt::format("reproduces {} {} (the paper states no number for it)", p.paper, p.figure);
  const std::optional<double> v = r.reproduced_value();
  const bool percent = p.quantity != "tau";
  const auto show = [percent](double x) {
    return percent ? fmt::format("{:.1f}%", 100.0 * x) : fmt::format("{:.4g}", x);
  };
  return fmt::format("reproduces {} {}: {} {} in the paper, {} here", p.paper, p.figure, p.quantity,
                     show(p.value),
                     v ? show(*v) : std::string("not measurable (more than one slot)"));
}

nlohmann::json RenderResult::to_json() const {
  const SkipCounts total = skip_total();
  nlohmann::json per_pair = nlohmann::json::array();
  for (std::size_t l = 0; l < skips.size(); ++l)
    for (std::size_t m = 0; m < skips[l].size(); ++m) {
      if (skips[l][m].total() == 0) continue;
      nlohmann::json j = skips[l][m].to_json();
      j["light"] = lights[l];
      j["material"] = materials[m];
      per_pair.push_back(std::move(j));
    }
  nlohmann::json units_json = nlohmann::json::array();
  for (const UnitRender& u : units) {
    // Operations saved against the standard test (skip only t <= 0, Källberg & Larsson §1): the
    // requests with t > 0 that the unit's own comparator skipped, times its per-request work.
    const auto beyond =
        static_cast<std::int64_t>(u.skipped) - static_cast<std::int64_t>(total.zero);
    nlohmann::json saved = nlohmann::json::object(), executed = nlohmann::json::object();
    for (const auto& [kind, n] : u.cost.ops_per_computed) {
      saved[kind] = n * static_cast<double>(beyond);
      executed[kind] = n * static_cast<double>(u.computed);
    }
    // Every request's own (the comparator, the merge buffer), as `glint sim` counts them
    // (eval/sim_report.cpp): one lane, one count.
    for (const auto& [kind, n] : u.cost.ops_per_request)
      executed[kind] = executed.value(kind, 0.0) + n * static_cast<double>(u.stats.vectors);
    units_json.push_back({{"unit", u.label},
                          {"file", u.file},
                          {"spec", u.spec},
                          {"image_error", u.error.to_json()},
                          {"heatmap_scale_lsb", u.heatmap_scale},
                          {"requests", u.stats.vectors},
                          {"skipped", u.skipped},
                          {"skipped_beyond_t_le_0", beyond},
                          {"skipped_fraction", unit_skipped_fraction(u)},
                          {"operations", executed},
                          {"operations_saved", saved},
                          {"area_ge", u.cost.area_ge},
                          {"critical_path", u.cost.critical_path},
                          {"errors", u.stats.errors_json()},
                          {"description", u.stats.description}});
    if (node) units_json.back()["node"] = u.cost.node_json();
    if (!u.energy.is_null()) units_json.back()["energy"] = u.energy;
    if (!u.energy_without_skip.is_null())
      units_json.back()["energy_without_skip"] = u.energy_without_skip;
    if (u.without_skip) units_json.back()["error_without_skip"] = without_skip_json(u);
  }
  return {{"glint_render_report", kRenderReportVersion},
          {"scene", scene_name},
          {"resolution", {width, height}},
          {"requests", requests},
          {"lobes", lobes},
          {"t_inputs", t_inputs()},
          {"lights", lights},
          {"materials", used_materials},
          {"chip", chip},
          {"meshes", meshes},
          {"slots", slots},
          {"skip",
           {{"fractions_of", "light x pixel pairs"},
            {"total", total.to_json()},
            {"per_light_material", per_pair}}},
          {"display", to_string(display)},
          {"eps_measure", to_string(eps_measure)},
          {"skip_only_image_error", skip_only_error.to_json()},
          {"skip_guarantee",
           {{"bound_lsb", skip_guarantee_lsb},
            {"holds", skip_within_guarantee},
            {"channel_over_tau_weight", skip_ratio}}},
          {"heat_scale", to_string(heat_scale)},
          {"reproduces", reproduces_json(*this)},
          {"units", units_json},
          {"files", render_file_names(*this)},
          {"float_images", float_images_json(*this)}};
}

RenderOutputs declare_render_outputs(OutputSet& outputs, const std::string& dir,
                                     const std::vector<std::string>& labels,
                                     const std::vector<std::string>& lights,
                                     const std::string& option) {
  outputs.make_folder(option, dir);
  RenderOutputs out;
  for (const std::string& name : render_file_names(labels, lights))
    out.files.emplace_back(name, &outputs.add(option + " (" + name + ")",
                                              (std::filesystem::path(dir) / name).string()));
  return out;
}

std::vector<PngRowWriter::Sink> render_png_sinks(const RenderOutputs& outputs) {
  std::vector<PngRowWriter::Sink> sinks;
  for (std::size_t i = 0; i + 1 < outputs.files.size(); ++i) {
    OutputFile* file = outputs.files[i].second;
    sinks.emplace_back([file](const std::uint8_t* data, std::size_t size) {
      file->stream().write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    });
  }
  return sinks;
}

void write_render(const RenderResult& r, const RenderOutputs& outputs, int threads) {
  if (render_file_names(r) != [&] {
        std::vector<std::string> names;
        for (const auto& f : outputs.files) names.push_back(f.first);
        return names;
      }())
    throw std::logic_error("write_render: the declared files are not the render's");
  if (r.images == RenderImages::kNone)
    throw std::logic_error("write_render: the render made no images (RenderImages::kNone)");
  if (r.images == RenderImages::kKeep) {
    std::vector<const Image8*> images{&r.reference, &r.reference_specular, &r.skip_mask};
    for (const Image8& mask : r.light_skip_masks) images.push_back(&mask);
    images.push_back(&r.skip_only);
    for (const UnitRender& u : r.units) {
      images.push_back(&u.image);
      images.push_back(&u.specular);
      images.push_back(&u.heatmap);
    }
    images.push_back(&r.legend);
    images.push_back(&r.contact_sheet);
    const std::vector<PngRowWriter::Sink> sinks = render_png_sinks(outputs);
    // Each file its own task: the encoders share nothing, and each writes only its own output.
    parallel_for(images.size(), threads, [&](std::size_t i) {
      PngRowWriter(images[i]->width, images[i]->height, sinks[i])
          .add_rows(images[i]->pixels.data(), images[i]->height);
    });
  }
  outputs.files.back().second->stream() << r.to_json().dump(2) << '\n';
}

void write_render(const RenderResult& r, const std::string& dir) {
  std::vector<std::string> labels;
  for (const UnitRender& u : r.units) labels.push_back(u.label);
  OutputSet outputs;
  const RenderOutputs files =
      declare_render_outputs(outputs, dir, labels, r.lights, "render folder");
  write_render(r, files);
  outputs.commit();
}

}  // namespace glint
