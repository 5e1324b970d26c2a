// PNG encoders side by side on the images `glint render` writes: stb_image_write (glint's encoder
// up to issue 28), libspng and libpng, each at a few low compression levels and filter rules, in
// one run on the same images. Every encoded file is decoded again (libspng) and its pixels
// compared with the image's: an encoder that changes a pixel is reported, not timed.
//   png_speed [--scene FILE] [--width W --height H] [--repeat N]
// Default: traces/scenes/teapot.json at 1920x1080 through every unit at its defaults (the images
// of `glint render`, contact sheet included). Prints per encoder the thread CPU seconds and wall
// seconds to encode every image once (best of --repeat, default 3), the total file size, and the
// CPU time against stb's.
#include <fmt/format.h>
#include <png.h>
#include <spng.h>
#include <stb_image_write.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "render/render.h"
#include "scene/scene.h"

namespace {

using Bytes = std::vector<std::uint8_t>;
using glint::Image8;

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

Bytes stb_encode(const Image8& im, int level) {
  Bytes out;
  stbi_write_png_compression_level = level;
  stbi_write_force_png_filter = -1;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* o = static_cast<Bytes*>(ctx);
        const auto* b = static_cast<const std::uint8_t*>(data);
        o->insert(o->end(), b, b + size);
      },
      &out, im.width, im.height, 3, im.pixels.data(), 3 * im.width);
  return out;
}

Bytes spng_encode(const Image8& im, int level, int filters, int strategy = -1) {
  spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  if (strategy >= 0) spng_set_option(ctx, SPNG_IMG_COMPRESSION_STRATEGY, strategy);
  spng_set_option(ctx, SPNG_IMG_COMPRESSION_LEVEL, level);
  spng_set_option(ctx, SPNG_FILTER_CHOICE, filters);
  spng_ihdr ihdr{};
  ihdr.width = static_cast<std::uint32_t>(im.width);
  ihdr.height = static_cast<std::uint32_t>(im.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = SPNG_COLOR_TYPE_TRUECOLOR;
  spng_set_ihdr(ctx, &ihdr);
  Bytes out;
  if (spng_encode_image(ctx, im.pixels.data(), im.pixels.size(), SPNG_FMT_PNG,
                        SPNG_ENCODE_FINALIZE) == 0) {
    std::size_t size = 0;
    int error = 0;
    void* buf = spng_get_png_buffer(ctx, &size, &error);
    if (buf) {
      out.assign(static_cast<std::uint8_t*>(buf), static_cast<std::uint8_t*>(buf) + size);
      std::free(buf);
    }
  }
  spng_ctx_free(ctx);
  return out;
}

Bytes libpng_encode(const Image8& im, int level, int filters) {
  Bytes out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return {};
  }
  png_set_write_fn(
      png, &out,
      [](png_structp p, png_bytep data, png_size_t n) {
        auto* o = static_cast<Bytes*>(png_get_io_ptr(p));
        o->insert(o->end(), data, data + n);
      },
      nullptr);
  png_set_compression_level(png, level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, filters);
  png_set_IHDR(png, info, static_cast<png_uint_32>(im.width), static_cast<png_uint_32>(im.height),
               8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  for (int y = 0; y < im.height; ++y)
    png_write_row(png, im.pixels.data() + static_cast<std::size_t>(y) * 3 * im.width);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

bool decodes_to(const Bytes& png, const Image8& im) {
  spng_ctx* ctx = spng_ctx_new(0);
  spng_set_png_buffer(ctx, png.data(), png.size());
  std::size_t size = 0;
  bool same = false;
  if (spng_decoded_image_size(ctx, SPNG_FMT_RGB8, &size) == 0 && size == im.pixels.size()) {
    Bytes pixels(size);
    same =
        spng_decode_image(ctx, pixels.data(), size, SPNG_FMT_RGB8, 0) == 0 && pixels == im.pixels;
  }
  spng_ctx_free(ctx);
  return same;
}

struct Encoder {
  std::string name;
  std::function<Bytes(const Image8&)> encode;
};

}  // namespace

int main(int argc, char* argv[]) {
  std::string scene_file = std::string(GLINT_SOURCE_DIR) + "/traces/scenes/teapot.json";
  int width = 1920, height = 1080, repeat = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--scene")) scene_file = argv[i + 1];
    if (!std::strcmp(argv[i], "--width")) width = std::stoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--height")) height = std::stoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--repeat")) repeat = std::stoi(argv[i + 1]);
  }
  glint::Scene scene = glint::load_scene(scene_file);
  scene.camera.width = width;
  scene.camera.height = height;
  glint::RenderOptions options;
  options.threads = 2;
  const glint::RenderResult r = glint::render_scene(scene, options);
  std::vector<const Image8*> images{&r.reference, &r.reference_specular, &r.skip_mask};
  for (const Image8& mask : r.light_skip_masks) images.push_back(&mask);
  images.push_back(&r.skip_only);
  for (const glint::UnitRender& u : r.units) {
    images.push_back(&u.image);
    images.push_back(&u.specular);
    images.push_back(&u.heatmap);
  }
  images.push_back(&r.legend);
  images.push_back(&r.contact_sheet);
  std::uint64_t raw = 0;
  for (const Image8* im : images) raw += im->pixels.size();
  fmt::print("{} at {}x{}: {} images, {:.1f} MB of pixels; best of {}\n", scene.name, width, height,
             images.size(), raw / 1e6, repeat);

  const int kAdaptive = SPNG_FILTER_CHOICE_ALL;
  std::vector<Encoder> encoders{
      {"stb level 8 (glint before)", [](const Image8& im) { return stb_encode(im, 8); }},
      {"stb level 1", [](const Image8& im) { return stb_encode(im, 1); }},
  };
  for (int level : {1, 2, 3, 6}) {
    encoders.push_back({fmt::format("libspng level {} adaptive", level),
                        [=](const Image8& im) { return spng_encode(im, level, kAdaptive); }});
  }
  for (int level : {1, 2}) {
    encoders.push_back({fmt::format("libspng level {} up", level), [=](const Image8& im) {
                          return spng_encode(im, level, SPNG_FILTER_CHOICE_UP);
                        }});
    encoders.push_back({fmt::format("libspng level {} sub", level), [=](const Image8& im) {
                          return spng_encode(im, level, SPNG_FILTER_CHOICE_SUB);
                        }});
  }
  for (int level : {1, 2, 3}) {
    encoders.push_back({fmt::format("libpng level {} adaptive", level), [=](const Image8& im) {
                          return libpng_encode(im, level, PNG_ALL_FILTERS);
                        }});
  }
  for (int level : {1, 2}) {
    encoders.push_back({fmt::format("libpng level {} up", level),
                        [=](const Image8& im) { return libpng_encode(im, level, PNG_FILTER_UP); }});
  }
  encoders.push_back({"libspng level 2 none", [](const Image8& im) {
                        return spng_encode(im, 2, SPNG_FILTER_CHOICE_NONE);
                      }});
  // zlib's strategies (zlib.h): 3 run-length only (Z_RLE), 0 the default.
  encoders.push_back({"libspng level 1 up rle", [](const Image8& im) {
                        return spng_encode(im, 1, SPNG_FILTER_CHOICE_UP, 3);
                      }});
  encoders.push_back({"libspng level 2 up default", [](const Image8& im) {
                        return spng_encode(im, 2, SPNG_FILTER_CHOICE_UP, 0);
                      }});
  encoders.push_back(
      {"glint encode_png (libpng)", [](const Image8& im) { return glint::encode_png(im); }});

  fmt::print("{:<28} {:>9} {:>9} {:>10} {:>9}  {}\n", "encoder", "cpu_s", "wall_s", "MB", "cpu/stb",
             "pixels");
  double stb_cpu = 0;
  for (const Encoder& e : encoders) {
    double best_cpu = 1e30, best_wall = 1e30;
    std::uint64_t bytes = 0;
    bool same = true;
    for (int k = 0; k < repeat; ++k) {
      bytes = 0;
      const double c0 = thread_cpu();
      const auto w0 = std::chrono::steady_clock::now();
      std::vector<Bytes> files;
      for (const Image8* im : images) files.push_back(e.encode(*im));
      const double cpu = thread_cpu() - c0;
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
      best_cpu = std::min(best_cpu, cpu);
      best_wall = std::min(best_wall, wall);
      for (std::size_t i = 0; i < files.size(); ++i) {
        bytes += files[i].size();
        if (k == 0) same = same && !files[i].empty() && decodes_to(files[i], *images[i]);
      }
    }
    if (stb_cpu == 0) stb_cpu = best_cpu;
    fmt::print("{:<28} {:>9.3f} {:>9.3f} {:>10.2f} {:>9.2f}  {}\n", e.name, best_cpu, best_wall,
               bytes / 1e6, best_cpu / stb_cpu, same ? "identical" : "DIFFERENT");
  }
  return 0;
}
