#include "sweep/canvas.h"

#include <fmt/format.h>

#include <cmath>

#include "io/html.h"

namespace glint {
namespace {

std::string hex(Rgb8 c) {
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

// Two decimals: positions to a hundredth of a pixel, the same text on every machine.
std::string num(double v) {
  std::string s = fmt::format("{:.2f}", v);
  if (s == "-0.00") s = "0.00";
  return s;
}

// DejaVu Sans: ascent 0.928 em, descent 0.236 em. draw_text's height spans both, so an SVG font
// of height / 1.164 em with its baseline 0.797 height below the top sets the same text.
constexpr double kEmPerHeight = 1.0 / 1.164;
constexpr double kBaseline = 0.928 / 1.164;

}  // namespace

double canvas_text_width(const std::string& s, int height) {
  return text_width(s, height);
}

SvgCanvas::SvgCanvas(int width, int height, Rgb8 background) : width_(width), height_(height) {
  rect(0, 0, width, height, background);
}

void SvgCanvas::line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) {
  body_ += fmt::format(
      "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\" "
      "stroke-linecap=\"round\"/>\n",
      num(x0), num(y0), num(x1), num(y1), hex(colour), num(width));
}

void SvgCanvas::circle(double cx, double cy, double r, Rgb8 fill, const char* role) {
  body_ += fmt::format("<circle{} cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\"/>\n",
                       role ? fmt::format(" class=\"{}\"", html_escape(role)) : std::string(),
                       num(cx), num(cy), num(r), hex(fill));
}

void SvgCanvas::rect(double x0, double y0, double x1, double y1, Rgb8 fill) {
  body_ += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>\n",
                       num(x0), num(y0), num(x1 - x0), num(y1 - y0), hex(fill));
}

void SvgCanvas::text(double x, double y, const std::string& s, int height, Rgb8 colour,
                     TextAnchor anchor) {
  const char* a = anchor == TextAnchor::kStart    ? "start"
                  : anchor == TextAnchor::kMiddle ? "middle"
                                                  : "end";
  body_ += fmt::format(
      "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"{}\" fill=\"{}\">{}</text>\n", num(x),
      num(y + kBaseline * height), num(kEmPerHeight * height), a, hex(colour), html_escape(s));
}

std::string SvgCanvas::finish() const {
  return fmt::format(
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
             "viewBox=\"0 0 {0} {1}\" font-family=\"DejaVu Sans, Verdana, sans-serif\">\n",
             width_, height_) +
         body_ + "</svg>\n";
}

void ImageCanvas::line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) {
  draw_line(image_, x0, y0, x1, y1, colour, width);
}

void ImageCanvas::circle(double cx, double cy, double r, Rgb8 fill, const char*) {
  fill_circle(image_, cx, cy, r, fill);
}

void ImageCanvas::rect(double x0, double y0, double x1, double y1, Rgb8 fill) {
  fill_rect(image_, x0, y0, x1, y1, fill);
}

void ImageCanvas::text(double x, double y, const std::string& s, int height, Rgb8 colour,
                       TextAnchor anchor) {
  const double w = text_width(s, height);
  const double left = anchor == TextAnchor::kStart    ? x
                      : anchor == TextAnchor::kMiddle ? x - w / 2
                                                      : x - w;
  draw_text(image_, static_cast<int>(std::lround(left)), static_cast<int>(std::lround(y)), s,
            colour, height);
}

}  // namespace glint
