// A chart is drawn once, on this small canvas interface, and comes out as SVG text (a writer of
// our own: deterministic text, no dependency) and as a PNG (glint's image layer: Image8, its
// anti-aliased shapes and DejaVu text). Debian has no plotting library that a C++ library can
// call without a runtime dependency; gnuplot would be an external process to drive and ship.
#pragma once

#include <string>

#include "image/image.h"

namespace glint {

enum class TextAnchor { kStart, kMiddle, kEnd };

class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) = 0;
  // `role`, when given, names what the circle stands for (the SVG's class attribute, e.g.
  // "point front"), so scripts and tests can find the data points among the legend's.
  virtual void circle(double cx, double cy, double r, Rgb8 fill, const char* role = nullptr) = 0;
  virtual void rect(double x0, double y0, double x1, double y1, Rgb8 fill) = 0;
  // Text `height` pixels tall (ascent to descent, as draw_text) with its top at y.
  virtual void text(double x, double y, const std::string& s, int height, Rgb8 colour,
                    TextAnchor anchor = TextAnchor::kStart) = 0;
};

// The text's width at a height, as both canvases lay it out (DejaVu Sans' advances).
double canvas_text_width(const std::string& s, int height);

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(int width, int height, Rgb8 background);
  void line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) override;
  void circle(double cx, double cy, double r, Rgb8 fill, const char* role = nullptr) override;
  void rect(double x0, double y0, double x1, double y1, Rgb8 fill) override;
  void text(double x, double y, const std::string& s, int height, Rgb8 colour,
            TextAnchor anchor) override;
  // The document: an XML declaration, <svg> and one element per call, in call order.
  std::string finish() const;

 private:
  int width_, height_;
  std::string body_;
};

class ImageCanvas : public Canvas {
 public:
  ImageCanvas(int width, int height, Rgb8 background) : image_(width, height, background) {}
  void line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) override;
  void circle(double cx, double cy, double r, Rgb8 fill, const char* role = nullptr) override;
  void rect(double x0, double y0, double x1, double y1, Rgb8 fill) override;
  void text(double x, double y, const std::string& s, int height, Rgb8 colour,
            TextAnchor anchor) override;
  const Image8& image() const { return image_; }

 private:
  Image8 image_;
};

}  // namespace glint
