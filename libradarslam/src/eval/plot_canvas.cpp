#include "plot_canvas.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"

namespace radarslam::eval::plot {

namespace {

std::string hex(Color c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string num(double v) { return fixed(v, 2); }

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string strokeAttributes(const Stroke& s) {
  std::string a = " stroke=\"" + hex(s.color) + "\" stroke-width=\"" + num(s.width) + "\"";
  if (s.dashed) a += " stroke-dasharray=\"" + num(4 * s.width + 2) + " " + num(3 * s.width + 1) + "\"";
  return a;
}

/// Hershey fonts are ASCII only: spell out the few non-ASCII characters our labels use.
std::string asciiOnly(const std::string& s) {
  static const std::pair<const char*, const char*> kReplace[] = {{"\xC2\xB0", " deg"},
                                                                 {"\xE2\x88\x92", "-"},
                                                                 {"\xC2\xB7", "|"},
                                                                 {"\xE2\x80\xA6", "..."},
                                                                 {"\xC3\x97", "x"}};
  std::string out = s;
  for (const auto& [from, to] : kReplace)
    for (auto pos = out.find(from); pos != std::string::npos; pos = out.find(from, pos + std::strlen(to)))
      out.replace(pos, std::strlen(from), to);
  out.erase(
      std::remove_if(out.begin(), out.end(), [](char c) { return static_cast<unsigned char>(c) >= 0x80; }),
      out.end());
  // " deg" after a digit reads "1.2 deg/m"; after a space ("[ deg") drop the extra space.
  for (auto pos = out.find("  deg"); pos != std::string::npos; pos = out.find("  deg")) out.erase(pos, 1);
  for (auto pos = out.find("[ deg"); pos != std::string::npos; pos = out.find("[ deg")) out.erase(pos + 1, 1);
  return out;
}

cv::Scalar bgr(Color c) { return cv::Scalar(c.b, c.g, c.r); }

constexpr int kShift = 3;  // sub-pixel bits for OpenCV drawing
constexpr double kOne = 1 << kShift;

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

}  // namespace

double textWidth(const std::string& text, double size) {
  std::size_t chars = 0;
  for (char c : text)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++chars;  // count UTF-8 code points
  return 0.58 * size * static_cast<double>(chars);
}

// ---- SVG ---------------------------------------------------------------------------------------

SvgCanvas::SvgCanvas(double width, double height) : Canvas(width, height) {}

void SvgCanvas::polyline(const std::vector<Pt>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  body_ += "<polyline fill=\"none\" stroke-linejoin=\"round\" stroke-linecap=\"round\"" +
           strokeAttributes(stroke) + " points=\"";
  for (std::size_t i = 0; i < points.size(); ++i)
    body_.append(i ? " " : "").append(fixed(points[i].x, 1)).append(",").append(fixed(points[i].y, 1));
  body_ += "\"/>\n";
}

void SvgCanvas::rect(Pt p, double w, double h, std::optional<Color> fill, std::optional<Stroke> stroke) {
  body_ += "<rect x=\"" + num(p.x) + "\" y=\"" + num(p.y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
           "\" fill=\"" + (fill ? hex(*fill) : std::string("none")) + "\"" +
           (stroke ? strokeAttributes(*stroke) : "") + "/>\n";
}

void SvgCanvas::circle(Pt c, double r, std::optional<Color> fill, std::optional<Stroke> stroke) {
  body_ += "<circle cx=\"" + num(c.x) + "\" cy=\"" + num(c.y) + "\" r=\"" + num(r) + "\" fill=\"" +
           (fill ? hex(*fill) : std::string("none")) + "\"" + (stroke ? strokeAttributes(*stroke) : "") +
           "/>\n";
}

void SvgCanvas::text(Pt at, const std::string& text, const TextStyle& s) {
  const char* anchor = s.anchor == Anchor::Start ? "start" : s.anchor == Anchor::Middle ? "middle" : "end";
  body_ += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y) + "\" font-size=\"" + num(s.size) + "\" fill=\"" +
           hex(s.color) + "\" text-anchor=\"" + anchor + "\"" + (s.bold ? " font-weight=\"bold\"" : "") +
           (s.vertical ? " transform=\"rotate(-90 " + num(at.x) + " " + num(at.y) + ")\"" : "") + ">" +
           xmlEscape(text) + "</text>\n";
}

std::string SvgCanvas::finish() const {
  const std::string w = num(width()), h = num(height());
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
         w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n<rect width=\"100%\" "
         "height=\"100%\" "
         "fill=\"#ffffff\"/>\n" +
         body_ + "</svg>\n";
}

// ---- PNG (OpenCV) ------------------------------------------------------------------------------

PngCanvas::PngCanvas(double width, double height, double scale)
    : Canvas(width, height),
      scale_(scale),
      image_(static_cast<int>(std::lround(height * scale)), static_cast<int>(std::lround(width * scale)),
             CV_8UC3, cv::Scalar(255, 255, 255)) {}

namespace {
cv::Point fx(Pt p, double scale) {
  return {static_cast<int>(std::lround(p.x * scale * kOne)),
          static_cast<int>(std::lround(p.y * scale * kOne))};
}
int thicknessPx(double width, double scale) {
  return std::max(1, static_cast<int>(std::lround(width * scale)));
}

/// Splits a polyline into dashes of `on` / gaps of `off` (in points) along its length.
std::vector<std::vector<Pt>> dashes(const std::vector<Pt>& pts, double on, double off) {
  std::vector<std::vector<Pt>> out;
  std::vector<Pt> cur{pts.front()};
  bool drawing = true;
  double left = on;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    Pt a = pts[i - 1];
    const Pt b = pts[i];
    double seg = std::hypot(b.x - a.x, b.y - a.y);
    while (seg > left) {
      const double t = left / seg;
      const Pt m{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      if (drawing) {
        cur.push_back(m);
        out.push_back(cur);
        cur.clear();
      } else
        cur = {m};
      drawing = !drawing;
      seg -= left;
      a = m;
      left = drawing ? on : off;
    }
    left -= seg;
    if (drawing) cur.push_back(b);
  }
  if (drawing && cur.size() >= 2) out.push_back(cur);
  return out;
}
}  // namespace

void PngCanvas::polyline(const std::vector<Pt>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  const std::vector<std::vector<Pt>> parts = stroke.dashed
                                                 ? dashes(points, 4 * stroke.width + 2, 3 * stroke.width + 1)
                                                 : std::vector<std::vector<Pt>>{points};
  std::vector<std::vector<cv::Point>> polys;
  for (const auto& part : parts) {
    std::vector<cv::Point> poly;
    for (const Pt& p : part) poly.push_back(fx(p, scale_));
    polys.push_back(std::move(poly));
  }
  cv::polylines(image_, polys, false, bgr(stroke.color), thicknessPx(stroke.width, scale_), cv::LINE_AA,
                kShift);
}

void PngCanvas::rect(Pt p, double w, double h, std::optional<Color> fill, std::optional<Stroke> stroke) {
  const cv::Point a = fx(p, scale_), b = fx({p.x + w, p.y + h}, scale_);
  if (fill) cv::rectangle(image_, a, b, bgr(*fill), cv::FILLED, cv::LINE_AA, kShift);
  if (stroke)
    cv::rectangle(image_, a, b, bgr(stroke->color), thicknessPx(stroke->width, scale_), cv::LINE_AA, kShift);
}

void PngCanvas::circle(Pt c, double r, std::optional<Color> fill, std::optional<Stroke> stroke) {
  const int radius = static_cast<int>(std::lround(r * scale_ * kOne));
  if (fill) cv::circle(image_, fx(c, scale_), radius, bgr(*fill), cv::FILLED, cv::LINE_AA, kShift);
  if (stroke)
    cv::circle(image_, fx(c, scale_), radius, bgr(stroke->color), thicknessPx(stroke->width, scale_),
               cv::LINE_AA, kShift);
}

void PngCanvas::text(Pt at, const std::string& utf8, const TextStyle& s) {
  const std::string text = asciiOnly(utf8);
  if (text.empty()) return;
  static const int kCapHeight = cv::getTextSize("H", kFont, 1.0, 1, nullptr).height;
  const double font_scale = 0.72 * s.size * scale_ / kCapHeight;
  const int thickness = std::max(1, static_cast<int>(std::lround(s.size * scale_ / 13.0))) + (s.bold ? 1 : 0);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, font_scale, thickness, &baseline);
  const double shift = s.anchor == Anchor::Start    ? 0.0
                       : s.anchor == Anchor::Middle ? size.width / 2.0
                                                    : size.width;
  const double x = at.x * scale_, y = at.y * scale_;
  if (!s.vertical) {
    cv::putText(image_, text, {static_cast<int>(std::lround(x - shift)), static_cast<int>(std::lround(y))},
                kFont, font_scale, bgr(s.color), thickness, cv::LINE_AA);
    return;
  }
  // Vertical: draw horizontally on a white tile, rotate it, and darken-blend it into the image.
  const int pad = thickness + 2;
  cv::Mat tile(size.height + baseline + 2 * pad, size.width + 2 * pad, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(tile, text, {pad, pad + size.height}, kFont, font_scale, bgr(s.color), thickness, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(tile, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  // The baseline start (pad, pad + h) of the tile lands at (pad + h, tile.cols - 1 - pad) when rotated;
  // the anchor moves the text start down the page by `shift`.
  const int left = static_cast<int>(std::lround(x)) - (pad + size.height);
  const int top = static_cast<int>(std::lround(y + shift)) - (tile.cols - 1 - pad);
  const cv::Rect dst =
      cv::Rect(left, top, rotated.cols, rotated.rows) & cv::Rect(0, 0, image_.cols, image_.rows);
  if (dst.empty()) return;
  const cv::Rect src(dst.x - left, dst.y - top, dst.width, dst.height);
  cv::Mat roi = image_(dst);
  cv::min(roi, rotated(src), roi);
}

void writeSvg(const std::string& path, const SvgCanvas& canvas) {
  writeTextAtomically(path, canvas.finish());
}

void writePng(const std::string& path, const PngCanvas& canvas) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", canvas.image(), bytes)) throw InputError(path, "PNG encoding failed");
  writeBytesAtomically(path, bytes);
}

// ---- helpers -----------------------------------------------------------------------------------

double niceStep(double raw) {
  if (!(raw > 0) || !std::isfinite(raw)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw * (1 - 1e-9)) return m * p;
  return 10 * p;
}

std::string fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, value);
  std::string s = buf;
  if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s.erase(0, 1);  // "-0.0" -> "0.0"
  return s;
}

std::string tickLabel(double value, double step) {
  const int decimals = step >= 1 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return fixed(value, decimals);
}

std::string shortLabel(const std::string& label, std::size_t max_chars) {
  std::string s = label;
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  const auto slash = s.find_last_of('/');
  if (slash != std::string::npos) s = s.substr(slash + 1);
  if (s.size() > max_chars) s = "..." + s.substr(s.size() - (max_chars - 3));
  return s;
}

}  // namespace radarslam::eval::plot
