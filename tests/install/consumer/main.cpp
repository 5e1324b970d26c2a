// A program that uses glint as a pure library (glint::core / glint-core.pc): it builds a Hast unit
// for one material and checks a few results against the accuracy contract, encodes a small image
// as PNG (the image layer needs libstb at link time) and calls the scene loader (which links
// tinyobjloader): the package must bring both along. No SystemC: it starts from its own main().
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "image/image.h"
#include "io/input_error.h"
#include "scene/scene.h"
#include "units/catalogue.h"
#include "units/common.h"

int main() {
  // n = 50 with Källberg's tau for eps = 1e-3 (0.87): the comparator skips t <= tau.
  const std::unique_ptr<glint::SpecularUnit> unit =
      glint::make_unit(glint::parse_unit_spec("hast"), {glint::MaterialParams{50, 0.87, false}});
  const glint::QFormat in = unit->in_format(), out = unit->out_format();
  bool ok = true;
  std::printf("glint consumer: %s\n", unit->canonical_spec().c_str());
  for (const double t : {1.0, 0.95, 0.9, 0.5}) {
    const std::int64_t t_raw = glint::quantize_input(t, in);
    const std::int64_t raw = unit->eval_with_skip(0, t_raw);
    const double value = std::ldexp(static_cast<double>(raw), -out.frac_bits);
    // The contract: exactly 1 at t = 1, exactly 0 when skipped, otherwise faithful (< 1 ulp) to
    // the unit's own real-valued model.
    const bool skipped = unit->skip(0, t_raw);
    const double model = skipped ? 0.0 : unit->model(0, t_raw);
    const bool good = (t == 1.0 ? raw == out.raw_one() : true) && (t == 0.5 ? skipped : !skipped) &&
                      std::fabs(value - model) < out.ulp();
    std::printf("  t %.2f raw %lld value %.6f %s\n", t, static_cast<long long>(raw), value,
                good ? "ok" : "WRONG");
    ok = ok && good;
  }
  glint::Image8 image(2, 1);
  image.set(1, 0, {glint::srgb8(0.5), 0, 0});
  const std::vector<std::uint8_t> png = glint::encode_png(image);
  const bool png_good = png.size() > 8 && png[1] == 'P' && png[2] == 'N' && png[3] == 'G';
  std::printf("  png %s\n", png_good ? "ok" : "WRONG");
  ok = ok && png_good;
  bool scene_ok = false;
  try {
    glint::load_scene("no-such-scene.json");
  } catch (const glint::InputError& e) {
    scene_ok = e.field() == "file";
  }
  std::printf("  load_scene of a missing file: %s\n", scene_ok ? "ok" : "WRONG");
  ok = ok && scene_ok;
  std::printf("glint consumer: %s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
