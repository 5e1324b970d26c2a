#include "render/render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <stdexcept>

#include "eval/chip_report.h"
#include "eval/energy.h"
#include "eval/parallel.h"
#include "io/input_error.h"
#include "render/image_error.h"
#include "render/render_sheet.h"
#include "scene/mesh_summary.h"
#include "scene/tracer.h"
#include "units/catalogue.h"
#include "units/chip.h"
#include "units/common.h"
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
// Images are composed a tile (strip) at a time, then copied into whole images (kKeep) or
// PNG-encoded at once and reduced for the contact sheet (kStream).
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
        tracer_(scene),
        mode_(options.images),
        factor_(sheet_factor(width_)),
        masked_lights_(std::min(lights_, kMaxLightSkipMasks)),
        reference_slots_(4 + masked_lights_) {
    out_.images = mode_;
    if (mode_ == RenderImages::kKeep) {
      out_.reference = out_.reference_specular = out_.skip_only = out_.skip_mask =
          Image8(width_, height_);
      out_.light_skip_masks.assign(masked_lights_, Image8(width_, height_));
      image_.assign(units_, Image8(width_, height_));
      specular_.assign(units_, Image8(width_, height_));
    }
    if (mode_ != RenderImages::kNone) {
      strip_.resize(reference_slots_ + 2 * units_);
      error_.assign(units_, std::vector<std::uint8_t>(static_cast<std::size_t>(width_) * height_));
      object_.assign(static_cast<std::size_t>(width_) * height_, 0);
    }
    if (!options.float_sinks.empty() && options.float_sinks.size() != 2 + units_)
      throw std::logic_error("render: float_sinks needs one sink per float image file");
    out_.float_format = options.float_format;
    if (mode_ == RenderImages::kStream) {
      if (options.png_sinks.size() != sheet_file() + 1)
        throw std::logic_error("render: kStream needs one PNG sink per image file");
      thumb_.resize(strip_.size());
      for (std::size_t slot = 0; slot < strip_.size(); ++slot)
        writer_.emplace_back(width_, height_, options.png_sinks[slot_file(slot)]);
    }
    acc_.resize(units_);
    for (std::size_t u = 0; u < units_; ++u) ulp_.push_back(ev_.units()[u]->out_format().ulp());
    if (options.node && options.gating) make_without_skip_lanes(*options.gating);
    out_.skips.assign(lights_, std::vector<SkipCounts>(scene.materials.size()));
  }

  void run() {
    // Streamed tiles are whole blocks of the contact sheet's reduction (but the last).
    const int tile_rows = std::min(mode_ == RenderImages::kStream
                                       ? (options_.tile_rows + factor_ - 1) / factor_ * factor_
                                       : options_.tile_rows,
                                   height_);
    for (int y0 = 0; y0 < height_; y0 += tile_rows) {
      y0_ = y0;
      rows_in_tile_ = std::min(height_, y0 + tile_rows) - y0;
      pixels_ = static_cast<std::size_t>(rows_in_tile_) * width_;
      make_requests();
      if (options_.on_requests) options_.on_requests(requests_.data(), requests_.size());
      ev_.add_batch(requests_.data(), requests_.size(), results_, options_.threads);
      if (off_ev_)
        off_ev_->add_batch(requests_.data(), requests_.size(), off_results_, options_.threads);
      out_.requests += requests_.size();
      index_lit_pixels();
      out_.shaded_pixels += lit_.size();
      accumulate_specular();
      compose_reference_pixels();
      for (Image8& strip : strip_)
        if (strip.height != rows_in_tile_) strip = Image8(width_, rows_in_tile_);
      parallel_for(1 + units_, options_.threads, [&](std::size_t task) {
        if (task == 0) {
          compose_reference();
        } else {
          compose_unit(task - 1);
        }
      });
      if (options_.progress)
        std::fprintf(stderr, "\rrender: %d/%d rows", y0 + rows_in_tile_, height_);
    }
    if (options_.progress) std::fprintf(stderr, "\n");
    finish();
  }

  // The contact sheet's tiles in compose_sheet's order: the reference, its specular term, the
  // skip mask and the per-light masks, then each unit's image, specular term and error map, reduced
  // by sheet_factor.
  std::vector<Image8> sheet_tiles() {
    std::vector<Image8> tiles;
    if (mode_ == RenderImages::kStream) {
      for (std::size_t slot = 0; slot + 1 < reference_slots_; ++slot)
        tiles.push_back(std::move(thumb_[slot]));
      for (std::size_t u = 0; u < units_; ++u) {
        tiles.push_back(std::move(thumb_[reference_slots_ + 2 * u]));
        tiles.push_back(std::move(thumb_[reference_slots_ + 2 * u + 1]));
        tiles.push_back(std::move(heat_thumb_[u]));
      }
      return tiles;
    }
    const auto reduce = [&](const Image8& image) {
      return factor_ > 1 ? downscale(image, factor_) : image;
    };
    tiles = {reduce(out_.reference), reduce(out_.reference_specular), reduce(out_.skip_mask)};
    for (const Image8& mask : out_.light_skip_masks) tiles.push_back(reduce(mask));
    for (std::size_t u = 0; u < units_; ++u) {
      const UnitRender& r = out_.units[u];
      tiles.push_back(reduce(r.image));
      tiles.push_back(reduce(r.specular));
      tiles.push_back(
          factor_ > 1 ? error_thumb(error_[u], object_, width_, height_, factor_, r.heatmap_scale)
                      : r.heatmap);
    }
    return tiles;
  }

  // The files of the images render_scene draws at the end (kStream).
  std::size_t legend_file() const { return reference_slots_ + 3 * units_; }
  std::size_t sheet_file() const { return legend_file() + 1; }

 private:
  static std::vector<UnitSpec> unit_specs(const RenderOptions& o) {
    std::vector<UnitSpec> specs = o.units;
    if (specs.empty())
      for (const std::string& name : default_unit_names()) specs.push_back(parse_unit_spec(name));
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

  // The tile's pixels with at least one request (lit_, in raster order) and each request's index
  // among them. No other pixel receives specular light from any source, so a unit's light is kept
  // for these alone: a scene sweep composes hundreds of units per tile, and most pixels are
  // background or face away from every light.
  void index_lit_pixels() {
    lit_.clear();
    request_lit_.resize(requests_.size());
    for (std::size_t k = 0; k < requests_.size(); ++k) {
      const std::uint32_t p = request_pixel_[k];
      if (lit_.empty() || lit_.back() != p) lit_.push_back(p);
      request_lit_[k] = static_cast<std::uint32_t>(lit_.size() - 1);
    }
  }

  // Sources of specular light: 0 the reference (with the skip statistics and the mask's classes),
  // 1 the reference with the skip alone, both per pixel; 2 + u unit u, per lit pixel. Each source
  // its own task.
  void accumulate_specular() {
    specular_light_.resize(2 + units_);
    parallel_for(1 + units_, options_.threads, [&](std::size_t task) {
      if (task == 0) {
        specular_light_[0].assign(pixels_, Rgb{});
        specular_light_[1].assign(pixels_, Rgb{});
        accumulate_reference();
        return;
      }
      const std::size_t u = task - 1;
      std::vector<Rgb>& spec = specular_light_[2 + u];
      spec.assign(lit_.size(), Rgb{});
      const std::int64_t* raw = results_.raw.data() + u * requests_.size();
      for (std::size_t k = 0; k < requests_.size(); ++k)
        add_scaled(spec[request_lit_[k]], request_colour(k), static_cast<double>(raw[k]) * ulp_[u]);
      if (!activity_.empty()) count_activity(u);
      if (const std::size_t j = off_index(u); j != kNoOff) {
        std::vector<Rgb>& off = off_light_[j];
        off.assign(lit_.size(), Rgb{});
        const std::int64_t* off_raw = off_results_.raw.data() + j * requests_.size();
        for (std::size_t k = 0; k < requests_.size(); ++k)
          add_scaled(off[request_lit_[k]], request_colour(k),
                     static_cast<double>(off_raw[k]) * off_ulp_[j]);
      }
    });
  }

  // The unit's switching activity on the tile's requests, in raster order (as glint sim counts a
  // vector file's: the same requests give the same energy).
  void count_activity(std::size_t u) {
    const SpecularUnit& unit = *ev_.units()[u];
    const SlotMap& slots = ev_.slots();
    for (const VectorRow& row : requests_)
      activity_[u].add(slots.slot(row), quantize_input(row.t, unit.in_format()));
    if (ActivityCounter* off = no_skip_activity_[u].get())
      for (const VectorRow& row : requests_)
        off->add(slots.slot(row), quantize_input(row.t, off->unit().in_format()));
  }

  // What the skip buys (issue 26, item 5): each lane with the skip beside the same lane without
  // its comparator (its spec with skip=off, every request computed), on the same requests: their
  // energies, and their errors measured alike, since a saving is fair only at equal error. The
  // lanes without the skip are an Evaluator of their own, so a render without --node does no
  // more than before.
  void make_without_skip_lanes(Gating gating) {
    std::vector<UnitSpec> off_specs;
    off_of_.assign(units_, kNoOff);
    for (std::size_t u = 0; u < units_; ++u) {
      const SpecularUnit& unit = *ev_.units()[u];
      if (!unit.comparator_enabled()) continue;
      UnitSpec spec = parse_unit_spec(unit.canonical_spec());
      const auto key = std::find_if(spec.keys.begin(), spec.keys.end(),
                                    [](const auto& k) { return k.first == "skip"; });
      if (key != spec.keys.end()) {
        key->second = "off";
      } else {
        spec.keys.emplace_back("skip", "off");
      }
      off_of_[u] = off_specs.size();
      off_specs.push_back(std::move(spec));
    }
    if (!off_specs.empty()) {
      off_ev_ = std::make_unique<Evaluator>(header_, off_specs, 8, options_.chip);
      off_light_.resize(off_specs.size());
      off_acc_.resize(off_specs.size());
      off_between_.resize(off_specs.size());
      for (const auto& unit : off_ev_->units()) off_ulp_.push_back(unit->out_format().ulp());
    }
    for (std::size_t u = 0; u < units_; ++u) {
      activity_.emplace_back(*ev_.units()[u], gating);
      no_skip_activity_.push_back(
          off_of_[u] == kNoOff
              ? nullptr
              : std::make_unique<ActivityCounter>(*off_ev_->units()[off_of_[u]], Gating::kNone));
    }
  }

  // The index of unit u's lane without the skip (kNoOff: none).
  static constexpr std::size_t kNoOff = static_cast<std::size_t>(-1);
  std::size_t off_index(std::size_t u) const { return off_of_.empty() ? kNoOff : off_of_[u]; }

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

  // Pixel p's final colour with specular light s.
  Rgb8 final_pixel(const Rgb& s, std::size_t p) const {
    const Rgb& d = diffuse_[p];
    return to_display8(scene_.display, Rgb{d.r + s.r, d.g + s.g, d.b + s.b});
  }

  // The highlight's extent and core are levels relative to the material's peak (10 % and 50 %),
  // not "8-bit code above 0" or "above eps": sRGB's steep toe makes a lobe of 1e-3 code 3, and the
  // threshold may drop up to eps per pixel (eps/K for each of K lights), so any level near eps
  // would measure the skip rather than the shape.
  ImageErrorAccumulator::Highlight highlight(const Rgb& s, std::size_t p) const {
    const double y = luminance(s);
    return {y > 0 && y >= 0.1 * peak_[p], y > 0 && y >= 0.5 * peak_[p]};
  }

  // The reference's final pixels and highlight, which every unit's error needs, and the pixels
  // without specular light: most of a unit's pixels (the background, and every request skipped or
  // at t <= 0), which then cost no display encoding per unit.
  void compose_reference_pixels() {
    ref8_.resize(pixels_);
    ref_highlight_.resize(pixels_);
    diffuse8_.resize(pixels_);
    for (std::size_t p = 0; p < pixels_; ++p) {
      diffuse8_[p] = to_display8(scene_.display, diffuse_[p]);
      ref8_[p] = final_pixel(specular_light_[0][p], p);
      ref_highlight_[p] = highlight(specular_light_[0][p], p);
    }
  }

  static bool dark(const Rgb& c) { return c.r == 0 && c.g == 0 && c.b == 0; }

  // Pixel p of the tile's strip.
  static void put(Image8& strip, std::size_t p, const Rgb8& c) {
    std::copy(c.begin(), c.end(), strip.pixels.begin() + static_cast<std::ptrdiff_t>(3 * p));
  }

  // The reference's linear light (plus the diffuse term if `diffuse`) to a float sink.
  void emit_float(std::size_t sink, bool diffuse) const {
    std::vector<float> rgb(3 * pixels_);
    const std::vector<Rgb>& light = specular_light_[0];
    for (std::size_t p = 0; p < pixels_; ++p) {
      const Rgb d = diffuse ? diffuse_[p] : Rgb{};
      rgb[3 * p] = static_cast<float>(d.r + light[p].r);
      rgb[3 * p + 1] = static_cast<float>(d.g + light[p].g);
      rgb[3 * p + 2] = static_cast<float>(d.b + light[p].b);
    }
    options_.float_sinks[sink](rgb.data(), rows_in_tile_);
  }

  // Unit u's linear specular light (zero off the lit pixels) to its float sink.
  void emit_unit_float(std::size_t u) const {
    std::vector<float> rgb(3 * pixels_, 0.0f);
    const std::vector<Rgb>& light = specular_light_[2 + u];
    for (std::size_t i = 0; i < lit_.size(); ++i) {
      const std::size_t p = lit_[i];
      rgb[3 * p] = static_cast<float>(light[i].r);
      rgb[3 * p + 1] = static_cast<float>(light[i].g);
      rgb[3 * p + 2] = static_cast<float>(light[i].b);
    }
    options_.float_sinks[2 + u](rgb.data(), rows_in_tile_);
  }

  void compose_reference() {
    if (!options_.float_sinks.empty()) {
      emit_float(0, true);
      emit_float(1, false);
    }
    const bool images = mode_ != RenderImages::kNone;
    for (std::size_t p = 0; p < pixels_; ++p) {
      const Rgb8 ref = ref8_[p];
      const Rgb8 skip_only = final_pixel(specular_light_[1][p], p);
      skip_acc_.add(ref, skip_only, ref_highlight_[p], highlight(specular_light_[1][p], p));
      if (!images) continue;
      put(strip_[0], p, ref);
      put(strip_[1], p, to_display8(scene_.display, specular_light_[0][p]));
      put(strip_[skip_only_slot()], p, skip_only);
      const auto grey = static_cast<std::uint8_t>((ref[0] * 54 + ref[1] * 183 + ref[2] * 19) >> 8);
      const bool object = skip_[p] != PixelSkip::kBackground;
      object_[static_cast<std::size_t>(y0_) * width_ + p] = object ? 1 : 0;
      put(strip_[2], p,
          object ? combined_skip_colour(lights_ - computed_lights_[p], lights_, grey) : Rgb8{});
      for (std::size_t l = 0; l < masked_lights_; ++l)
        put(strip_[3 + l], p, skip_colour(light_skip_[l * pixels_ + p], grey));
    }
    if (!images) return;
    for (std::size_t slot = 0; slot < reference_slots_; ++slot) emit(slot);
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

  // The strips of the reference's images: reference, its specular term, the skip mask, the
  // per-light masks, then the skip-only image (files in that order, render_file_names).
  std::size_t skip_only_slot() const { return reference_slots_ - 1; }
  std::size_t slot_file(std::size_t slot) const {
    if (slot < reference_slots_) return slot;
    const std::size_t k = slot - reference_slots_;
    return reference_slots_ + 3 * (k / 2) + k % 2;
  }
  std::size_t heatmap_file(std::size_t unit) const { return reference_slots_ + 3 * unit + 2; }

  void compose_unit(std::size_t u) {
    const bool images = mode_ != RenderImages::kNone;
    Image8* image = images ? &strip_[reference_slots_ + 2 * u] : nullptr;
    Image8* specular = images ? &strip_[reference_slots_ + 2 * u + 1] : nullptr;
    const std::vector<Rgb>& light = specular_light_[2 + u];
    if (!options_.float_sinks.empty()) emit_unit_float(u);
    // A pixel without requests has no specular light in any source: the unit's pixel is the
    // reference's (d + 0 is d exactly), with no error and no highlight, so it is only counted.
    acc_[u].add_equal_unlit(pixels_ - lit_.size());
    const std::size_t j = off_index(u);
    const std::vector<Rgb>* off = j == kNoOff ? nullptr : &off_light_[j];
    if (off) off_acc_[j].add_equal_unlit(pixels_ - lit_.size());
    std::uint8_t* error_row =
        images ? error_[u].data() + static_cast<std::size_t>(y0_) * width_ : nullptr;
    if (images)
      for (std::size_t p = 0; p < pixels_; ++p) {
        put(*image, p, diffuse8_[p]);
        put(*specular, p, black8_);
        error_row[p] = 0;
      }
    for (std::size_t i = 0; i < lit_.size(); ++i) {
      const std::size_t p = lit_[i];
      // d + 0 is d exactly, and no light is no highlight: the same figures as the general case.
      const bool none = dark(light[i]);
      const Rgb8 img = none ? diffuse8_[p] : final_pixel(light[i], p);
      const int error =
          acc_[u].add(ref8_[p], img, ref_highlight_[p],
                      none ? ImageErrorAccumulator::Highlight{} : highlight(light[i], p));
      if (off != nullptr) compose_without_skip(u, i, img);
      if (!images) continue;
      put(*image, p, img);
      put(*specular, p, none ? black8_ : to_display8(scene_.display, light[i]));
      error_row[p] = static_cast<std::uint8_t>(error);
    }
    if (!images) return;
    emit(reference_slots_ + 2 * u);
    emit(reference_slots_ + 2 * u + 1);
  }

  // Lit pixel i of unit u's lane without the skip: its error, as the lane's own is measured, and
  // how it differs from the lane's final pixel `lane`.
  void compose_without_skip(std::size_t u, std::size_t i, const Rgb8& lane) {
    const std::size_t j = off_of_[u];
    const std::size_t p = lit_[i];
    const Rgb& light = off_light_[j][i];
    const bool none = dark(light);
    const Rgb8 img = none ? diffuse8_[p] : final_pixel(light, p);
    off_acc_[j].add(ref8_[p], img, ref_highlight_[p],
                    none ? ImageErrorAccumulator::Highlight{} : highlight(light, p));
    int between = 0;
    for (int c = 0; c < 3; ++c) between = std::max(between, std::abs(int{img[c]} - int{lane[c]}));
    OffBetween& b = off_between_[j];
    b.pixels += between > 0;
    b.max_lsb = std::max(b.max_lsb, between);
  }

  // The whole image a slot's strip is part of (kKeep).
  Image8& whole(std::size_t slot) {
    if (slot == 0) return out_.reference;
    if (slot == 1) return out_.reference_specular;
    if (slot == 2) return out_.skip_mask;
    if (slot == skip_only_slot()) return out_.skip_only;
    if (slot < reference_slots_) return out_.light_skip_masks[slot - 3];
    const std::size_t k = slot - reference_slots_;
    return k % 2 ? specular_[k / 2] : image_[k / 2];
  }

  // A slot's strip, complete: into its whole image, or encoded and reduced.
  void emit(std::size_t slot) {
    const Image8& strip = strip_[slot];
    if (mode_ == RenderImages::kKeep) {
      std::copy(strip.pixels.begin(), strip.pixels.end(),
                whole(slot).pixels.begin() + static_cast<std::ptrdiff_t>(3 * y0_ * width_));
      return;
    }
    writer_[slot].add_rows(strip.pixels.data(), strip.height);
    if (slot == skip_only_slot()) return;  // the skip-only image has no tile
    const Image8 reduced = factor_ > 1 ? downscale(strip, factor_) : strip;
    Image8& thumb = thumb_[slot];
    thumb.width = reduced.width;
    thumb.height += reduced.height;
    thumb.pixels.insert(thumb.pixels.end(), reduced.pixels.begin(), reduced.pixels.end());
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
    const std::vector<UnitStats> off_stats = off_ev_ ? off_ev_->stats() : std::vector<UnitStats>{};
    const std::vector<std::string> labels = render_unit_labels(unit_specs(options_));
    const std::vector<std::string> stems = render_file_stems(labels);
    // The shared scale: the largest error of any unit (at least 1 LSB), so that a colour means the
    // same error on every map; --heat-scale own gives each unit its own, which shows a 1-LSB
    // unit's pattern beside a 60-LSB one at the cost of comparing colours.
    double shared_scale = 1;
    for (std::size_t u = 0; u < units_; ++u)
      shared_scale = std::max(shared_scale, acc_[u].result().max_lsb);
    out_.heat_scale = options_.heat_scale;
    out_.node = options_.node;
    for (std::size_t u = 0; u < units_; ++u) {
      UnitRender r;
      r.label = labels[u];
      r.file = stems[u];
      r.spec = stats[u].spec;
      if (mode_ == RenderImages::kKeep) {
        r.image = std::move(image_[u]);
        r.specular = std::move(specular_[u]);
      }
      r.error = acc_[u].result();
      r.stats = stats[u];
      r.cost = unit_cost(*ev_.units()[u]);
      r.skipped = stats[u].skipped;
      r.computed = stats[u].vectors - stats[u].skipped;
      if (!activity_.empty())
        if (const EnergyWeights* w = find_energy(r.cost.node)) {
          r.energy =
              energy_json(lane_energy(r.cost, activity_[u].activity(), *w), out_.shaded_pixels);
          if (const ActivityCounter* off = no_skip_activity_[u].get()) {
            r.energy_without_skip = energy_json(
                lane_energy(unit_cost(off->unit()), off->activity(), *w), out_.shaded_pixels);
            r.energy_without_skip["spec"] = off->unit().canonical_spec();
          }
        }
      if (const std::size_t j = off_index(u); j != kNoOff && !r.energy_without_skip.is_null())
        r.without_skip =
            UnitRender::WithoutSkip{off_stats[j].spec, off_acc_[j].result(), off_stats[j],
                                    off_between_[j].pixels, off_between_[j].max_lsb};
      r.heatmap_scale =
          options_.heat_scale == HeatScale::kShared ? shared_scale : std::max(1.0, r.error.max_lsb);
      out_.units.push_back(std::move(r));
    }
    if (mode_ != RenderImages::kNone) draw_heatmaps();
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

  // Each unit's error map (a task each), drawn at the end where the shared scale is known.
  // kStream encodes it at once and keeps only its reduced tile; the error maps are freed as they
  // are drawn.
  void draw_heatmaps() {
    heat_thumb_.resize(units_);
    parallel_for(units_, options_.threads, [&](std::size_t u) {
      UnitRender& r = out_.units[u];
      Image8 heatmap = error_map(std::vector<double>(error_[u].begin(), error_[u].end()), object_,
                                 width_, height_, r.heatmap_scale);
      if (mode_ == RenderImages::kKeep) {
        r.heatmap = std::move(heatmap);
        return;
      }
      PngRowWriter(heatmap.width, heatmap.height, options_.png_sinks[heatmap_file(u)])
          .add_rows(heatmap.pixels.data(), heatmap.height);
      heat_thumb_[u] =
          factor_ > 1 ? error_thumb(error_[u], object_, width_, height_, factor_, r.heatmap_scale)
                      : std::move(heatmap);
      std::vector<std::uint8_t>().swap(error_[u]);
    });
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
  const RenderImages mode_;
  const int factor_;                   // the contact sheet's reduction
  const std::size_t masked_lights_;    // lights with a skip mask of their own
  const std::size_t reference_slots_;  // strips before the units' (see skip_only_slot)
  std::vector<double> ulp_;
  // Whole-image results per unit (kKeep).
  std::vector<Image8> image_, specular_;
  std::vector<std::vector<std::uint8_t>> error_;  // LSBs per pixel (largest channel)
  std::vector<Image8> strip_;                     // per slot, the current tile's rows
  std::vector<PngRowWriter> writer_;              // per slot (kStream)
  std::vector<Image8> thumb_;                     // per slot, reduced so far (kStream)
  std::vector<Image8> heat_thumb_;                // per unit (kStream)
  std::vector<ImageErrorAccumulator> acc_;
  std::vector<ActivityCounter> activity_;  // per unit, with node and gating
  // With node, the lanes with the skip built without it (make_without_skip_lanes): per unit the
  // index of its own (kNoOff: none) and its activity (null: none); per such lane its results on
  // the tile, specular light per lit pixel, image error and difference from the lane's pixels.
  std::vector<std::size_t> off_of_;
  std::unique_ptr<Evaluator> off_ev_;
  BatchResults off_results_;
  std::vector<double> off_ulp_;
  std::vector<std::vector<Rgb>> off_light_;
  std::vector<ImageErrorAccumulator> off_acc_;
  struct OffBetween {
    std::uint64_t pixels = 0;
    int max_lsb = 0;
  };
  std::vector<OffBetween> off_between_;
  std::vector<std::unique_ptr<ActivityCounter>> no_skip_activity_;
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
  std::vector<std::vector<Rgb>> specular_light_;  // [source][pixel, or lit pixel for units]
  std::vector<std::uint32_t> lit_;                // tile pixels with a request, ascending
  std::vector<std::uint32_t> request_lit_;        // each request's index in lit_
  std::vector<PixelSkip> skip_;
  std::vector<PixelSkip> light_skip_;           // [light][pixel] of the masked lights
  std::vector<std::uint32_t> computed_lights_;  // lights computed per pixel
  std::vector<std::uint8_t> object_;            // whole image: nonzero where an object shows
  std::vector<double> peak_;  // the pixel material's peak specular luminance under every light
  std::vector<Rgb8> ref8_;
  std::vector<Rgb8> diffuse8_;  // the final pixel without specular light
  const Rgb8 black8_ = to_display8(scene_.display, Rgb{});
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

std::uint64_t render_bytes(std::uint64_t pixels, std::size_t units, RenderImages images,
                           int threads, std::size_t masked_lights) {
  switch (images) {
    case RenderImages::kKeep:
      return pixels * (kRenderBytesPerPixel + kRenderBytesPerPixelUnit * units + 3 * masked_lights);
    case RenderImages::kStream:
      return pixels *
             (kStreamBytesPerPixel + kStreamBytesPerPixelUnit * units +
              kStreamBytesPerHeatmap *
                  std::min<std::uint64_t>(units, static_cast<std::uint64_t>(std::max(threads, 1))));
    case RenderImages::kNone:
      break;
  }
  return 0;
}

RenderResult render_scene(const Scene& scene, const RenderOptions& options) {
  if (options.tile_rows < 1) throw std::invalid_argument("render: tile_rows must be >= 1");
  const std::uint64_t pixels = static_cast<std::uint64_t>(scene.camera.width) *
                               static_cast<std::uint64_t>(scene.camera.height);
  const std::size_t units =
      options.units.empty() ? default_unit_names().size() : options.units.size();
  const std::size_t masked_lights = std::min(scene.lights.size(), kMaxLightSkipMasks);
  const std::uint64_t bytes =
      render_bytes(pixels, units, options.images, options.threads, masked_lights);
  if (bytes > kMaxRenderBytes) {
    const std::string rule =
        options.images == RenderImages::kKeep
            ? fmt::format("{} + {} x units + 3 x {} masked lights", kRenderBytesPerPixel,
                          kRenderBytesPerPixelUnit, masked_lights)
            : fmt::format("{} + {} x units + {} x min(threads, units)", kStreamBytesPerPixel,
                          kStreamBytesPerPixelUnit, kStreamBytesPerHeatmap);
    throw InputError(scene.file, 0, "camera.resolution",
                     fmt::format("{} x {} pixels through {} unit{} need about {} MiB, more than "
                                 "the limit of {} MiB per render (about {} bytes per pixel): "
                                 "lower the resolution or render fewer units at a time",
                                 scene.camera.width, scene.camera.height, units,
                                 units == 1 ? "" : "s", bytes >> 20, kMaxRenderBytes >> 20, rule));
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
  if (options.images == RenderImages::kNone) return out;

  compose_sheet(out, renderer.sheet_tiles());
  if (options.images == RenderImages::kStream) {
    // The legend and the sheet are the last two files (render_file_names).
    const std::size_t legend = options.png_sinks.size() - 2;
    for (Image8* image : {&out.legend, &out.contact_sheet}) {
      PngRowWriter(image->width, image->height,
                   options.png_sinks[legend + (image == &out.contact_sheet ? 1 : 0)])
          .add_rows(image->pixels.data(), image->height);
      *image = Image8();
    }
  }
  return out;
}

}  // namespace glint
