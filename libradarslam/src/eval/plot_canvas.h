#pragma once
// Private to the eval module: one drawing interface with two back ends, so each plot is drawn once
// and written both as SVG (text we generate) and as PNG (OpenCV, anti-aliased, white background).
// Coordinates are in "points": y grows downwards, like SVG; the PNG back end scales them.
#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <vector>

namespace radarslam::eval::plot {

struct Pt {
  double x = 0, y = 0;
};

struct Color {
  unsigned char r = 0, g = 0, b = 0;
};

inline constexpr Color kBlack{0, 0, 0};
inline constexpr Color kWhite{255, 255, 255};

struct Stroke {
  Color color;
  double width = 1.0;
  bool dashed = false;
};

enum class Anchor { Start, Middle, End };

struct TextStyle {
  double size = 12;  ///< font size in points (em height)
  Color color = kBlack;
  Anchor anchor = Anchor::Start;
  bool bold = false;
  bool vertical = false;  ///< rotated 90 degrees counter-clockwise (reads bottom to top)
};

/// Approximate rendered width of `text` (same estimate for both back ends, used for layout).
double textWidth(const std::string& text, double size);

class Canvas {
 public:
  Canvas(double width, double height) : width_(width), height_(height) {}
  virtual ~Canvas() = default;
  double width() const { return width_; }
  double height() const { return height_; }

  virtual void polyline(const std::vector<Pt>& points, const Stroke& stroke) = 0;
  void line(Pt a, Pt b, const Stroke& stroke) { polyline({a, b}, stroke); }
  virtual void rect(Pt top_left, double w, double h, std::optional<Color> fill,
                    std::optional<Stroke> stroke) = 0;
  virtual void circle(Pt centre, double radius, std::optional<Color> fill, std::optional<Stroke> stroke) = 0;
  /// `at` is the start (or middle/end, per anchor) of the text's baseline.
  virtual void text(Pt at, const std::string& text, const TextStyle& style) = 0;

 private:
  double width_, height_;
};

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(double width, double height);
  void polyline(const std::vector<Pt>& points, const Stroke& stroke) override;
  void rect(Pt top_left, double w, double h, std::optional<Color> fill,
            std::optional<Stroke> stroke) override;
  void circle(Pt centre, double radius, std::optional<Color> fill, std::optional<Stroke> stroke) override;
  void text(Pt at, const std::string& text, const TextStyle& style) override;
  std::string finish() const;  ///< the complete SVG document

 private:
  std::string body_;
};

class PngCanvas : public Canvas {
 public:
  /// `scale` pixels per point (2 gives a sharp image on high-density screens).
  PngCanvas(double width, double height, double scale = 2.0);
  void polyline(const std::vector<Pt>& points, const Stroke& stroke) override;
  void rect(Pt top_left, double w, double h, std::optional<Color> fill,
            std::optional<Stroke> stroke) override;
  void circle(Pt centre, double radius, std::optional<Color> fill, std::optional<Stroke> stroke) override;
  void text(Pt at, const std::string& text, const TextStyle& style) override;
  const cv::Mat& image() const { return image_; }

 private:
  double scale_;
  cv::Mat image_;  // BGR, 8-bit
};

/// Draws with `draw` into both back ends and writes `<stem>.svg` and `<stem>.png` atomically.
/// Returns the two paths.
template <typename Draw>
std::vector<std::string> renderBoth(const std::string& stem, double width, double height, Draw&& draw);

void writeSvg(const std::string& path, const SvgCanvas& canvas);
void writePng(const std::string& path, const PngCanvas& canvas);

// ---- small helpers shared by the plots ---------------------------------------------------------

/// 1, 2 or 5 times a power of ten, the smallest such value >= raw (raw > 0).
double niceStep(double raw);
/// A tick label for `value` on an axis whose ticks are `step` apart ("200", "0.5", "-1.25").
std::string tickLabel(double value, double step);
/// "%.<decimals>f" that never prints "-0".
std::string fixed(double value, int decimals);
/// The file name of a path-like label, shortened with a leading "..." to at most `max_chars`.
std::string shortLabel(const std::string& label, std::size_t max_chars = 48);

template <typename Draw>
std::vector<std::string> renderBoth(const std::string& stem, double width, double height, Draw&& draw) {
  SvgCanvas svg(width, height);
  draw(static_cast<Canvas&>(svg));
  PngCanvas png(width, height);
  draw(static_cast<Canvas&>(png));
  const std::string svg_path = stem + ".svg", png_path = stem + ".png";
  writeSvg(svg_path, svg);
  writePng(png_path, png);
  return {svg_path, png_path};
}

}  // namespace radarslam::eval::plot
