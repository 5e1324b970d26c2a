#include "render/render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "eval/chip_report.h"
#include "eval/parallel.h"
#include "io/input_error.h"
#include "render/image_error.h"
#include "render/render_sheet.h"
#include "scene/mesh_summary.h"
#include "scene/tracer.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace glint {
namespace {

// How a pixel's requests went: computed by at least one light, else skipped by tau for at least
// one light, else skipped by t <= 0 (or facing away) for every light. Per light (the per-light
// masks) the same classes for that light's pair alone.
enum class PixelSkip : std::uint8_t { kBackground, kZero, kTau, kComputed };

void add_scaled(Rgb& acc, const Rgb& colour, double s) {
  acc.r += colour.r * s;
  acc.g += colour.g * s;
  acc.b += colour.b * s;
}

// The slot's luminance (eq.3): SlotMap::c_y under the luminance measure; under the channel
// measure its c_y holds the largest channel weight, and the luminance is of its channel weights.
double c_y_of(const SlotMap& slots, std::size_t s) {
  return slots.eps_measure == EpsMeasure::kLuminance ? slots.c_y[s]
                                                     : luminance(slots.pixel_weight[s]);
}

// A pixel's 8-bit codes in the scene's display encoding (reference/pixel_error.h).
Rgb8 to_display8(DisplayEncoding e, const Rgb& c) {
  return {display_code8(e, c.r), display_code8(e, c.g), display_code8(e, c.b)};
}

// The scene's request header with the run's eps measure.
VectorHeader request_header(const Scene& scene, const RenderOptions& options,
                            std::vector<std::int32_t>* header_of) {
  VectorHeader h = scene_request_header(scene, header_of);
  h.eps_measure = options.eps_measure;
  return h;
}

// The materials objects use, in scene order.
std::vector<std::uint32_t> used_materials(const Scene& scene) {
  std::set<std::uint32_t> used;
  for (const Mesh& m : scene.meshes) used.insert(m.material);
  for (const Sphere& s : scene.spheres) used.insert(s.material);
  for (const Plane& p : scene.planes) used.insert(p.material);
  return {used.begin(), used.end()};
}

// The requests of one image row, made on its own thread and joined in raster order.
struct RowRequests {
  std::vector<VectorRow> rows;
  std::vector<std::uint32_t> pixel;        // the tile pixel of each request
  std::vector<std::uint32_t> facing_away;  // light * materials + material of each pair skipped
};

// Renders a scene a tile of rows at a time. Every stage writes only its own outputs (a row, a
// source of specular light, a unit's images), so the bytes never depend on the thread count.
class SceneRenderer {
 public:
  SceneRenderer(const Scene& scene, const RenderOptions& options, RenderResult& out)
      : scene_(scene),
        options_(options),
        out_(out),
        width_(scene.camera.width),
        height_(scene.camera.height),
        lights_(scene.lights.size()),
        header_(request_header(scene, options, &header_of_)),
        ev_(header_, unit_specs(options), 8, options.chip),
        units_(ev_.units().size()),
        tracer_(scene) {
    out_.reference = out_.reference_specular = out_.skip_only = out_.skip_mask =
        Image8(width_, height_);
    masked_lights_ = std::min(lights_, kMaxLightSkipMasks);
    out_.light_skip_masks.assign(masked_lights_, Image8(width_, height_));
    object_.assign(static_cast<std::size_t>(width_) * height_, 0);
    image_.assign(units_, Image8(width_, height_));
    specular_.assign(units_, Image8(width_, height_));
    error_.assign(units_, std::vector<std::uint8_t>(static_cast<std::size_t>(width_) * height_));
    acc_.resize(units_);
    for (std::size_t u = 0; u < units_; ++u) ulp_.push_back(ev_.units()[u]->out_format().ulp());
    out_.skips.assign(lights_, std::vector<SkipCounts>(scene.materials.size()));
  }

  void run() {
    const int tile_rows = std::min(options_.tile_rows, height_);
    for (int y0 = 0; y0 < height_; y0 += tile_rows) {
      y0_ = y0;
      rows_in_tile_ = std::min(height_, y0 + tile_rows) - y0;
      pixels_ = static_cast<std::size_t>(rows_in_tile_) * width_;
      make_requests();
      if (options_.on_requests) options_.on_requests(requests_.data(), requests_.size());
      ev_.add_batch(requests_.data(), requests_.size(), results_, options_.threads);
      out_.requests += requests_.size();
      accumulate_specular();
      compose_reference();
      parallel_for(units_, options_.threads, [&](std::size_t u) { compose_unit(u); });
      if (options_.progress)
        std::fprintf(stderr, "\rrender: %d/%d rows", y0 + rows_in_tile_, height_);
    }
    if (options_.progress) std::fprintf(stderr, "\n");
    finish();
  }

  // Each unit's per-pixel error in LSBs (its largest channel), row-major.
  const std::vector<std::vector<std::uint8_t>>& error_lsb() const { return error_; }
  // Nonzero where a pixel shows an object, row-major.
  const std::vector<std::uint8_t>& object() const { return object_; }

 private:
  static std::vector<UnitSpec> unit_specs(const RenderOptions& o) {
    std::vector<UnitSpec> specs = o.units;
    if (specs.empty())
      for (const std::string& name : unit_names()) specs.push_back(parse_unit_spec(name));
    return specs;
  }

  // Ray-casts the tile and makes one request per visible pixel and light facing it; the diffuse
  // term needs no unit.
  void make_requests() {
    samples_.resize(pixels_);
    diffuse_.assign(pixels_, Rgb{});
    skip_.assign(pixels_, PixelSkip::kBackground);
    computed_lights_.assign(pixels_, 0);
    light_skip_.assign(masked_lights_ * pixels_, PixelSkip::kBackground);
    peak_.assign(pixels_, 0.0);
    per_row_.resize(static_cast<std::size_t>(rows_in_tile_));
    parallel_for(per_row_.size(), options_.threads, [&](std::size_t r) {
      const int y = y0_ + static_cast<int>(r);
      tracer_.trace_rows(y, y + 1, samples_.data() + r * width_);
      RowRequests& out = per_row_[r];
      out.rows.clear();
      out.pixel.clear();
      out.facing_away.clear();
      for (std::size_t p = r * width_; p < (r + 1) * width_; ++p) make_pixel_requests(p, out);
    });
    requests_.clear();
    request_pixel_.clear();
    for (const RowRequests& r : per_row_) {
      requests_.insert(requests_.end(), r.rows.begin(), r.rows.end());
      request_pixel_.insert(request_pixel_.end(), r.pixel.begin(), r.pixel.end());
      for (std::uint32_t pair : r.facing_away)
        ++out_.skips[pair / scene_.materials.size()][pair % scene_.materials.size()].facing_away;
    }
  }

  void make_pixel_requests(std::size_t p, RowRequests& out) {
    const SurfaceSample& s = samples_[p];
    if (!s.hit) {
      diffuse_[p] = scene_.background;
      return;
    }
    const SceneMaterial& mat = scene_.materials[s.material];
    const Rgb& a = scene_.ambient;
    diffuse_[p] = Rgb{a.r * mat.diffuse.r, a.g * mat.diffuse.g, a.b * mat.diffuse.b};
    skip_[p] = PixelSkip::kZero;
    for (std::size_t l = 0; l < masked_lights_; ++l)
      light_skip_[l * pixels_ + p] = PixelSkip::kZero;
    for (std::size_t l = 0; l < lights_; ++l) {
      const Rgb& i = scene_.lights[l].intensity;
      peak_[p] += c_y(i, mat.specular);
      const LightSample ls = light_sample(scene_, s, l);
      if (ls.n_dot_l <= 0) {
        out.facing_away.push_back(
            static_cast<std::uint32_t>(l * scene_.materials.size() + s.material));
        continue;
      }
      add_scaled(diffuse_[p], Rgb{i.r * mat.diffuse.r, i.g * mat.diffuse.g, i.b * mat.diffuse.b},
                 ls.n_dot_l);
      VectorRow row;
      // Rounding can leave |t| a hair above 1 for unit vectors; the lobe peaks at t = 1.
      row.t = std::clamp(mat.lobe == Lobe::kPhong ? ls.t_phong : ls.t_blinn, -1.0, 1.0);
      row.material = static_cast<std::uint32_t>(header_of_[s.material]);
      row.light = static_cast<std::int32_t>(l);
      row.x = static_cast<std::int32_t>(p % width_);
      row.y = y0_ + static_cast<std::int32_t>(p / width_);
      out.rows.push_back(row);
      out.pixel.push_back(static_cast<std::uint32_t>(p));
    }
  }

  Rgb request_colour(std::size_t k) const {
    const Rgb& ks = scene_.materials[samples_[request_pixel_[k]].material].specular;
    const Rgb& i = scene_.lights[static_cast<std::size_t>(requests_[k].light)].intensity;
    return Rgb{ks.r * i.r, ks.g * i.g, ks.b * i.b};
  }

  // Sources of specular light: 0 the reference (with the skip statistics and the mask's classes),
  // 1 the reference with the skip alone, 2 + u unit u; each source its own task.
  void accumulate_specular() {
    specular_light_.resize(2 + units_);
    for (auto& s : specular_light_) s.assign(pixels_, Rgb{});
    parallel_for(1 + units_, options_.threads, [&](std::size_t task) {
      if (task == 0) {
        accumulate_reference();
        return;
      }
      const std::size_t u = task - 1;
      std::vector<Rgb>& spec = specular_light_[2 + u];
      const std::int64_t* raw = results_.raw.data() + u * requests_.size();
      for (std::size_t k = 0; k < requests_.size(); ++k)
        add_scaled(spec[request_pixel_[k]], request_colour(k),
                   static_cast<double>(raw[k]) * ulp_[u]);
    });
  }

  void accumulate_reference() {
    const SlotMap& slots = ev_.slots();
    for (std::size_t k = 0; k < requests_.size(); ++k) {
      const VectorRow& row = requests_[k];
      const std::size_t p = request_pixel_[k];
      const MaterialParams& params = slots.params[slots.slot(row)];
      SkipCounts& counts = out_.skips[static_cast<std::size_t>(row.light)][samples_[p].material];
      const bool tau_skip = params.always_skip || row.t <= params.tau;
      const auto l = static_cast<std::size_t>(row.light);
      PixelSkip* light_skip = l < masked_lights_ ? &light_skip_[l * pixels_ + p] : nullptr;
      if (row.t <= 0) {
        ++counts.zero;
      } else if (tau_skip) {
        ++counts.tau;
        if (skip_[p] == PixelSkip::kZero) skip_[p] = PixelSkip::kTau;
        if (light_skip) *light_skip = PixelSkip::kTau;
      } else {
        ++counts.computed;
        ++computed_lights_[p];
        skip_[p] = PixelSkip::kComputed;
        if (light_skip) *light_skip = PixelSkip::kComputed;
      }
      const Rgb colour = request_colour(k);
      add_scaled(specular_light_[0][p], colour, results_.reference[k]);
      if (!tau_skip && row.t > 0) add_scaled(specular_light_[1][p], colour, results_.reference[k]);
    }
  }

  Rgb8 final_pixel(std::size_t source, std::size_t p) const {
    const Rgb& d = diffuse_[p];
    const Rgb& s = specular_light_[source][p];
    return to_display8(scene_.display, Rgb{d.r + s.r, d.g + s.g, d.b + s.b});
  }

  // The highlight's extent and core are levels relative to the material's peak (10 % and 50 %),
  // not "8-bit code above 0" or "above eps": sRGB's steep toe makes a lobe of 1e-3 code 3, and the
  // threshold may drop up to eps per pixel (eps/K for each of K lights), so any level near eps
  // would measure the skip rather than the shape.
  ImageErrorAccumulator::Highlight highlight(std::size_t source, std::size_t p) const {
    const double y = luminance(specular_light_[source][p]);
    return {y > 0 && y >= 0.1 * peak_[p], y > 0 && y >= 0.5 * peak_[p]};
  }

  int x_of(std::size_t p) const { return static_cast<int>(p % width_); }
  int y_of(std::size_t p) const { return y0_ + static_cast<int>(p / width_); }

  void compose_reference() {
    ref8_.resize(pixels_);
    ref_highlight_.resize(pixels_);
    for (std::size_t p = 0; p < pixels_; ++p) {
      const int x = x_of(p), y = y_of(p);
      const Rgb8 ref = ref8_[p] = final_pixel(0, p);
      ref_highlight_[p] = highlight(0, p);
      out_.reference.set(x, y, ref);
      out_.reference_specular.set(x, y, to_display8(scene_.display, specular_light_[0][p]));
      const Rgb8 skip_only = final_pixel(1, p);
      out_.skip_only.set(x, y, skip_only);
      skip_acc_.add(ref, skip_only, ref_highlight_[p], highlight(1, p));
      const auto grey = static_cast<std::uint8_t>((ref[0] * 54 + ref[1] * 183 + ref[2] * 19) >> 8);
      const bool object = skip_[p] != PixelSkip::kBackground;
      object_[static_cast<std::size_t>(y) * width_ + x] = object ? 1 : 0;
      out_.skip_mask.set(
          x, y,
          object ? combined_skip_colour(lights_ - computed_lights_[p], lights_, grey) : Rgb8{});
      for (std::size_t l = 0; l < masked_lights_; ++l)
        out_.light_skip_masks[l].set(x, y, skip_colour(light_skip_[l * pixels_ + p], grey));
    }
  }

  static Rgb8 skip_colour(PixelSkip s, std::uint8_t grey) {
    switch (s) {
      case PixelSkip::kZero:
        return kSkipZeroColour;
      case PixelSkip::kTau:
        return kSkipTauColour;
      case PixelSkip::kComputed:
        return {grey, grey, grey};
      case PixelSkip::kBackground:
        break;
    }
    return {0, 0, 0};
  }

  void compose_unit(std::size_t u) {
    for (std::size_t p = 0; p < pixels_; ++p) {
      const int x = x_of(p), y = y_of(p);
      const Rgb8 img = final_pixel(2 + u, p);
      image_[u].set(x, y, img);
      specular_[u].set(x, y, to_display8(scene_.display, specular_light_[2 + u][p]));
      error_[u][static_cast<std::size_t>(y) * width_ + x] = static_cast<std::uint8_t>(
          acc_[u].add(ref8_[p], img, ref_highlight_[p], highlight(2 + u, p)));
    }
  }

  void finish() {
    out_.skip_only_error = skip_acc_.result();
    const SlotMap& slot_map = ev_.slots();
    out_.display = scene_.display;
    out_.eps_measure = slot_map.eps_measure;
    out_.skip_ratio = slot_map.skip_ratio;
    out_.skip_guarantee_lsb = skip_guarantee_lsb(scene_.display, scene_.eps, slot_map.skip_ratio);
    out_.skip_within_guarantee = out_.skip_only_error.max_lsb <= out_.skip_guarantee_lsb;
    const std::vector<UnitStats> stats = ev_.stats();
    const std::vector<std::string> labels = render_unit_labels(unit_specs(options_));
    const std::vector<std::string> stems = render_file_stems(labels);
    // The shared scale: the largest error of any unit (at least 1 LSB), so that a colour means the
    // same error on every map; --heat-scale own gives each unit its own, which shows a 1-LSB
    // unit's pattern beside a 60-LSB one at the cost of comparing colours.
    double shared_scale = 1;
    for (std::size_t u = 0; u < units_; ++u)
      shared_scale = std::max(shared_scale, acc_[u].result().max_lsb);
    out_.heat_scale = options_.heat_scale;
    for (std::size_t u = 0; u < units_; ++u) {
      UnitRender r;
      r.label = labels[u];
      r.file = stems[u];
      r.spec = stats[u].spec;
      r.image = std::move(image_[u]);
      r.specular = std::move(specular_[u]);
      r.error = acc_[u].result();
      r.stats = stats[u];
      r.cost = unit_cost(*ev_.units()[u]);
      r.skipped = stats[u].skipped;
      r.computed = stats[u].vectors - stats[u].skipped;
      r.heatmap_scale =
          options_.heat_scale == HeatScale::kShared ? shared_scale : std::max(1.0, r.error.max_lsb);
      const std::vector<double> lsb(error_[u].begin(), error_[u].end());
      r.heatmap = error_map(lsb, object_, width_, height_, r.heatmap_scale);
      out_.units.push_back(std::move(r));
    }
    const SlotMap& slots = ev_.slots();
    out_.chip = chip_json(ev_.chip(), slots);
    out_.slots = nlohmann::json::array();
    for (std::size_t s = 0; s < slots.params.size(); ++s) {
      const MaterialParams& p = slots.params[s];
      out_.slots.push_back({{"name", p.name},
                            {"lobe", to_string(slots.lobe[s])},
                            {"shininess", p.shininess},
                            {"c_y", c_y_of(slots, s)},
                            {"pixel_weight", slots.pixel_weight_max[s]},
                            {"tau", p.tau},
                            {"always_skip", p.always_skip}});
    }
  }

  const Scene& scene_;
  const RenderOptions& options_;
  RenderResult& out_;
  const int width_, height_;
  const std::size_t lights_;
  std::vector<std::int32_t> header_of_;
  const VectorHeader header_;
  Evaluator ev_;
  const std::size_t units_;
  const SceneTracer tracer_;
  std::vector<double> ulp_;
  // Whole-image results per unit.
  std::vector<Image8> image_, specular_;
  std::vector<std::vector<std::uint8_t>> error_;  // LSBs per pixel (largest channel)
  std::vector<ImageErrorAccumulator> acc_;
  ImageErrorAccumulator skip_acc_;
  // The current tile.
  int y0_ = 0, rows_in_tile_ = 0;
  std::size_t pixels_ = 0;
  std::vector<SurfaceSample> samples_;
  std::vector<RowRequests> per_row_;
  std::vector<VectorRow> requests_;
  std::vector<std::uint32_t> request_pixel_;
  BatchResults results_;
  std::vector<Rgb> diffuse_;                      // ambient + diffuse, shared by every image
  std::vector<std::vector<Rgb>> specular_light_;  // [source][pixel], linear
  std::vector<PixelSkip> skip_;
  std::size_t masked_lights_ = 0;               // lights with a skip mask of their own
  std::vector<PixelSkip> light_skip_;           // [light][pixel] of the masked lights
  std::vector<std::uint32_t> computed_lights_;  // lights computed per pixel
  std::vector<std::uint8_t> object_;            // whole image: nonzero where an object shows
  std::vector<double> peak_;  // the pixel material's peak specular luminance under every light
  std::vector<Rgb8> ref8_;
  std::vector<ImageErrorAccumulator::Highlight> ref_highlight_;
};

}  // namespace

std::vector<std::string> render_light_names(const Scene& scene) {
  std::vector<std::string> names;
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
    names.push_back(scene.lights[l].name.empty() ? fmt::format("light {}", l)
                                                 : scene.lights[l].name);
  return names;
}

VectorHeader scene_request_header(const Scene& scene, std::vector<std::int32_t>* header_of) {
  VectorHeader h = scene_vector_header(scene);
  const std::vector<VectorMaterial> all = std::move(h.materials);
  h.materials.clear();
  if (header_of) header_of->assign(scene.materials.size(), -1);
  for (std::uint32_t m : used_materials(scene)) {
    if (header_of) (*header_of)[m] = static_cast<std::int32_t>(h.materials.size());
    h.materials.push_back(all[m]);
  }
  return h;
}

std::uint64_t render_bytes(std::uint64_t pixels, std::size_t units) {
  return pixels * (kRenderBytesPerPixel + kRenderBytesPerPixelUnit * units);
}

RenderResult render_scene(const Scene& scene, const RenderOptions& options) {
  if (options.tile_rows < 1) throw std::invalid_argument("render: tile_rows must be >= 1");
  const std::uint64_t pixels = static_cast<std::uint64_t>(scene.camera.width) *
                               static_cast<std::uint64_t>(scene.camera.height);
  const std::size_t units = options.units.empty() ? unit_names().size() : options.units.size();
  if (render_bytes(pixels, units) > kMaxRenderBytes) {
    throw InputError(
        scene.file, 0, "camera.resolution",
        fmt::format("{} x {} pixels through {} unit{} need about {} MiB, more than the limit of {} "
                    "MiB per render (about {} + {} x units bytes per pixel): lower the resolution "
                    "or render fewer units at a time",
                    scene.camera.width, scene.camera.height, units, units == 1 ? "" : "s",
                    render_bytes(pixels, units) >> 20, kMaxRenderBytes >> 20, kRenderBytesPerPixel,
                    kRenderBytesPerPixelUnit));
  }
  RenderResult out;
  out.scene_name = scene.name;
  out.meshes = meshes_json(scene);
  out.width = scene.camera.width;
  out.height = scene.camera.height;
  std::set<std::string> lobes;
  for (const SceneMaterial& m : scene.materials) out.materials.push_back(m.name);
  out.lights = render_light_names(scene);
  for (std::uint32_t m : used_materials(scene)) {
    out.used_materials.push_back(scene.materials[m].name);
    lobes.insert(to_string(scene.materials[m].lobe));
  }
  out.lobes.assign(lobes.begin(), lobes.end());

  out.eps = scene.eps;
  out.reproduces = scene.reproduces;
  SceneRenderer renderer(scene, options, out);
  renderer.run();
  compose_sheet(out, renderer.error_lsb(), renderer.object());
  return out;
}

}  // namespace glint
