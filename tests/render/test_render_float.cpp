// Float outputs (glint render --float): EXR and PFM round-trip exactly through their readers,
// in any batches of rows; a render's float images are the linear light its 8-bit images encode;
// the CLI writes them beside the PNGs, names them in the report, and refuses a bad format before
// writing anything.
#include <fcntl.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "image/float_image.h"
#include "reference/pixel_error.h"
#include "render/render.h"
#include "scene/scene.h"
#include "test_support.h"
#include "units/catalogue.h"

namespace glint {
namespace {

int open_for_writing(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  EXPECT_GE(fd, 0) << path;
  return fd;
}

TEST(FloatImage, RoundTripsExactlyInAnyBatches) {
  const int w = 37, h = 23;
  std::vector<float> rgb(3 * w * h);
  for (std::size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = static_cast<float>(i % 7) * 0.3f - 0.25f + 1e-7f * static_cast<float>(i);
  rgb[5] = 1e30f;  // beyond half's range: the files hold 32-bit floats
  test::TempDir dir;
  for (FloatFormat f : {FloatFormat::kExr, FloatFormat::kPfm}) {
    SCOPED_TRACE(to_string(f));
    const std::string path = dir.file("a." + to_string(f));
    FloatRowWriter writer(f, open_for_writing(path), w, h, path);
    for (int y = 0; y < h; y += 5) writer.add_rows(rgb.data() + 3 * w * y, std::min(5, h - y));
    EXPECT_THROW(writer.add_rows(rgb.data(), 1), std::logic_error);
    writer.finish();
    const FloatImage back = read_float_image(path);
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    EXPECT_TRUE(back.rgb == rgb);
  }
  EXPECT_EQ(parse_float_format("pfm"), FloatFormat::kPfm);
  EXPECT_THROW(parse_float_format("tiff"), std::invalid_argument);
}

TEST(FloatImage, MissingRowsAreRefused) {
  test::TempDir dir;
  const std::string path = dir.file("short.exr");
  FloatRowWriter writer(FloatFormat::kExr, open_for_writing(path), 4, 4, path);
  const std::vector<float> row(12, 0.5f);
  writer.add_rows(row.data(), 1);
  EXPECT_THROW(writer.finish(), std::logic_error);
}

// The float images are the light the 8-bit images encode: every float pixel, encoded for the
// scene's display, gives the PNG's code (to within the one code a float's rounding can move a
// value across a code's edge, and that only rarely).
TEST(RenderFloat, FloatImagesAreTheLinearLightOfThePngs) {
  Scene scene = load_scene(std::string(GLINT_SOURCE_DIR) + "/traces/scenes/multi.json");
  scene.camera.width = 160;
  scene.camera.height = 120;
  test::TempDir dir;
  for (FloatFormat f : {FloatFormat::kExr, FloatFormat::kPfm}) {
    SCOPED_TRACE(to_string(f));
    RenderOptions o;
    o.units = {parse_unit_spec("pow"), parse_unit_spec("schlick")};
    o.threads = 2;
    o.float_format = f;
    const std::vector<std::string> names = render_float_file_names(render_unit_labels(o.units), f);
    std::vector<std::unique_ptr<FloatRowWriter>> writers;
    for (const std::string& name : names) {
      writers.push_back(std::make_unique<FloatRowWriter>(
          f, open_for_writing(dir.file(name)), scene.camera.width, scene.camera.height, name));
      o.float_sinks.emplace_back(
          [w = writers.back().get()](const float* rgb, int rows) { w->add_rows(rgb, rows); });
    }
    const RenderResult r = render_scene(scene, o);
    for (const auto& w : writers) w->finish();
    EXPECT_EQ(r.to_json().at("float_images").at("files"), names);
    const std::vector<const Image8*> images{&r.reference, &r.reference_specular,
                                            &r.units[0].specular, &r.units[1].specular};
    for (std::size_t i = 0; i < names.size(); ++i) {
      SCOPED_TRACE(names[i]);
      const FloatImage fi = read_float_image(dir.file(names[i]));
      ASSERT_EQ(fi.width, images[i]->width);
      ASSERT_EQ(fi.height, images[i]->height);
      std::size_t off_by_one = 0, lit = 0;
      for (std::size_t k = 0; k < fi.rgb.size(); ++k) {
        const int code = display_code8(scene.display, fi.rgb[k]);
        const int png = images[i]->pixels[k];
        ASSERT_LE(std::abs(code - png), 1) << "value " << k;
        off_by_one += code != png;
        lit += fi.rgb[k] > 0;
      }
      EXPECT_LE(off_by_one, fi.rgb.size() / 1000);
      EXPECT_GT(lit, 0u);  // not an image of zeros
    }
  }
}

TEST(RenderFloat, CliWritesThemBesideThePngsOrNothing) {
  test::TempDir dir;
  const std::string scene = std::string(GLINT_SOURCE_DIR) + "/traces/scenes/small.json";
  const test::CliRun bad =
      test::run_glint(dir.path(), "render '" + scene + "' -o out --unit lut --float tiff");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("--float"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
  const test::CliRun ok =
      test::run_glint(dir.path(), "render '" + scene + "' -o out --unit lut --float exr --json");
  ASSERT_EQ(ok.status, 0) << ok.err;
  const nlohmann::json report = nlohmann::json::parse(ok.out);
  EXPECT_EQ(report.at("float_images").at("format"), "exr");
  for (const auto& name : report.at("float_images").at("files")) {
    const FloatImage fi = read_float_image(dir.file("out/" + name.get<std::string>()));
    EXPECT_EQ(fi.width, report.at("resolution")[0]);
  }
  EXPECT_EQ(report.at("float_images").at("files").size(), 3u);
}

}  // namespace
}  // namespace glint
