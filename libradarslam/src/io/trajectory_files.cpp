#include "radarslam/io/trajectory_files.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>

#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "radarslam/core/log.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {

constexpr double kMaxTiltDeg = 30.0;  // beyond this a pose is not "planar" (warning only)

struct Line {
  std::size_t number = 0;  // 1-based line number in the file
  std::vector<std::string> fields;
};

/// Concatenation without `"literal" + std::string` (GCC 12 reports a false -Wrestrict on it).
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  (s.append(parts), ...);
  return s;
}

std::string at(const fs::path& file, std::size_t line) {
  return cat(file.string(), ":", std::to_string(line));
}

/// The data lines of a text file: blank lines and '#' comments skipped, fields split on whitespace.
std::vector<Line> readDataLines(const fs::path& file) {
  requireRegularFile(file);
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), fs::exists(file) ? "cannot read file" : "file not found");
  std::vector<Line> lines;
  std::string text;
  std::size_t number = 0;
  while (std::getline(in, text)) {
    ++number;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    Line line{number, {}};
    std::istringstream fields(text);
    for (std::string f; fields >> f;) line.fields.push_back(f);
    lines.push_back(std::move(line));
  }
  if (in.bad()) throw InputError(file.string(), "read error");
  return lines;
}

double parseNumber(const std::string& text, const fs::path& file, std::size_t line, const char* what) {
  const char* begin = text.data() + (!text.empty() && text[0] == '+' ? 1 : 0);
  const char* end = text.data() + text.size();
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || ptr != end)
    throw InputError(at(file, line), cat("cannot parse ", what, " '", text, "' as a number"));
  if (!std::isfinite(v)) throw InputError(at(file, line), cat(what, " is not finite ('", text, "')"));
  return v;
}

StampNs parseStamp(const std::string& text, const fs::path& file, std::size_t line) {
  StampNs t = 0;
  if (!parseStampText(text, t)) throw InputError(at(file, line), cat("cannot parse timestamp '", text, "'"));
  return t;
}

void checkIncreasing(const Trajectory& traj, const fs::path& file, std::size_t line) {
  if (traj.size() >= 2 && traj.back().stamp <= traj[traj.size() - 2].stamp)
    throw InputError(at(file, line), cat("timestamp ", formatStampSeconds(traj.back().stamp),
                                         " s does not increase (previous pose: ",
                                         formatStampSeconds(traj[traj.size() - 2].stamp), " s)"));
}

void checkPosition(const StampedPose& p, const fs::path& file, std::size_t line) {
  if (std::abs(p.pose.x) > kMaxCoordinateM || std::abs(p.pose.y) > kMaxCoordinateM)
    throw InputError(at(file, line),
                     cat("position (", std::to_string(p.pose.x), ", ", std::to_string(p.pose.y),
                         ") is farther than 1e7 m from the origin"));
}

/// Remembers the largest tilt of the poses' z axis from vertical (up or down) for one warning.
struct TiltCheck {
  double worst_deg = 0.0;
  std::size_t worst_line = 0;
  void add(double r22, std::size_t line) {
    const double tilt = std::acos(std::min(1.0, std::abs(r22))) * 180.0 / std::numbers::pi;
    if (tilt > worst_deg) worst_deg = tilt, worst_line = line;
  }
  void report(const fs::path& file) const {
    if (worst_deg > kMaxTiltDeg)
      logger().logFmt(mrpt::system::LVL_WARN,
                      "%s:%zu: pose tilted %.0f deg from the x-y plane; radarslam evaluates x, y and yaw "
                      "about z (convert camera-frame poses first)",
                      file.string().c_str(), worst_line, worst_deg);
  }
};

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

}  // namespace

bool parseStampText(const std::string& text, StampNs& out) {
  if (text.empty()) return false;
  if (text.find_first_of("eE") != std::string::npos) {  // KITTI times.txt: "1.036000e-01"
    double s = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), s);
    if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(s) || std::abs(s) > 9.2e9)
      return false;
    out = static_cast<StampNs>(std::llround(s * 1e9));
    return true;
  }
  const auto dot = text.find('.');
  if (dot == std::string::npos) return parseStampByDigits(text, out);  // integer: unit by digit count
  // Exact decimal seconds: "1547120788.016733" = 1547120788 s + 016733000 ns.
  std::string_view whole(text.data(), dot), frac = std::string_view(text).substr(dot + 1);
  const bool negative = !whole.empty() && whole[0] == '-';
  if (!whole.empty() && (whole[0] == '-' || whole[0] == '+')) whole.remove_prefix(1);
  const auto digits = [](std::string_view s) {
    return std::all_of(s.begin(), s.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  };
  if (!digits(whole) || !digits(frac) || whole.size() > 10 || (whole.empty() && frac.empty())) return false;
  StampNs ns = 0;
  for (char c : whole) ns = ns * 10 + (c - '0');
  StampNs sub = 0;
  for (std::size_t i = 0; i < 9; ++i) sub = sub * 10 + (i < frac.size() ? frac[i] - '0' : 0);
  if (ns > (std::numeric_limits<StampNs>::max() - sub) / kNsPerSec) return false;  // int64 ns overflow
  ns = ns * kNsPerSec + sub;
  out = negative ? -ns : ns;
  return true;
}

std::string formatStampSeconds(StampNs t) {
  const bool negative = t < 0;
  const std::uint64_t a = negative ? static_cast<std::uint64_t>(-(t + 1)) + 1 : static_cast<std::uint64_t>(t);
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%s%llu.%09llu", negative ? "-" : "",
                static_cast<unsigned long long>(a / kNsPerSec),
                static_cast<unsigned long long>(a % kNsPerSec));
  return buf;
}

TrajectoryFormat parseTrajectoryFormat(const std::string& name, const std::string& where) {
  const std::string n = lowercase(name);
  if (n == "tum") return TrajectoryFormat::Tum;
  if (n == "kitti") return TrajectoryFormat::Kitti;
  if (n == "auto") return TrajectoryFormat::Auto;
  throw InputError(where, cat("unknown trajectory format '", name, "' (expected tum, kitti or auto)"));
}

std::string toString(TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::Tum:
      return "tum";
    case TrajectoryFormat::Kitti:
      return "kitti";
    case TrajectoryFormat::Auto:
      break;
  }
  return "auto";
}

TrajectoryFormat detectTrajectoryFormat(const fs::path& file) {
  const auto lines = readDataLines(file);
  if (lines.empty()) throw InputError(file.string(), "no poses in file");
  const std::size_t n = lines.front().fields.size();
  if (n == 8) return TrajectoryFormat::Tum;
  if (n == 12 || n == 13) return TrajectoryFormat::Kitti;
  throw InputError(at(file, lines.front().number),
                   cat("cannot tell the trajectory format from ", std::to_string(n),
                       " columns (TUM has 8: t x y z qx qy qz qw; KITTI has 12: a row-major 3x4 pose)"));
}

Trajectory readTumTrajectory(const fs::path& file) {
  Trajectory traj;
  TiltCheck tilt;
  for (const Line& line : readDataLines(file)) {
    if (line.fields.size() != 8)
      throw InputError(at(file, line.number), cat("expected 8 numbers (t x y z qx qy qz qw), found ",
                                                  std::to_string(line.fields.size()), " fields"));
    StampedPose p;
    p.stamp = parseStamp(line.fields[0], file, line.number);
    static constexpr std::array<const char*, 7> kNames{"x", "y", "z", "qx", "qy", "qz", "qw"};
    std::array<double, 7> v{};
    for (std::size_t i = 0; i < 7; ++i) v[i] = parseNumber(line.fields[i + 1], file, line.number, kNames[i]);
    const auto [x, y, z, qx, qy, qz, qw] = v;
    (void)z;
    const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (std::abs(norm - 1.0) > 1e-2)
      throw InputError(at(file, line.number),
                       cat("quaternion (qx qy qz qw) has norm ", fixed(norm, 6), ", not 1"));
    const double r00 = 1.0 - 2.0 * (qy * qy + qz * qz) / (norm * norm);
    const double r10 = 2.0 * (qx * qy + qw * qz) / (norm * norm);
    tilt.add(1.0 - 2.0 * (qx * qx + qy * qy) / (norm * norm), line.number);
    p.pose = mrpt::math::TPose2D(x, y, std::atan2(r10, r00));
    checkPosition(p, file, line.number);
    traj.push_back(p);
    checkIncreasing(traj, file, line.number);
  }
  if (traj.empty()) throw InputError(file.string(), "no poses in file");
  tilt.report(file);
  return traj;
}

std::vector<StampNs> readStampFile(const fs::path& file) {
  std::vector<StampNs> stamps;
  for (const Line& line : readDataLines(file)) {
    if (line.fields.size() != 1)
      throw InputError(at(file, line.number), cat("expected one timestamp per line, found ",
                                                  std::to_string(line.fields.size()), " fields"));
    stamps.push_back(parseStamp(line.fields[0], file, line.number));
    if (stamps.size() >= 2 && stamps.back() <= stamps[stamps.size() - 2])
      throw InputError(at(file, line.number), cat("timestamp ", line.fields[0], " does not increase"));
  }
  return stamps;
}

fs::path kittiStampsCompanion(const fs::path& kitti_file) {
  std::string name = kitti_file.stem().string();
  name.append(".times.txt");
  return kitti_file.parent_path() / name;
}

Trajectory readKittiTrajectory(const fs::path& file, const std::vector<StampNs>& stamps_in) {
  std::vector<StampNs> stamps = stamps_in;
  fs::path stamps_origin = "<stamps>";
  if (stamps.empty() && fs::exists(kittiStampsCompanion(file))) {
    stamps_origin = kittiStampsCompanion(file);
    stamps = readStampFile(stamps_origin);
  }
  const auto lines = readDataLines(file);
  Trajectory traj;
  TiltCheck tilt;
  for (const Line& line : lines) {
    const std::size_t n = line.fields.size();
    if (n != 12 && n != 13)
      throw InputError(at(file, line.number),
                       cat("expected 12 numbers (row-major 3x4 pose) or a stamp and 12 numbers, found ",
                           std::to_string(n), " fields"));
    if (n != lines.front().fields.size())
      throw InputError(at(file, line.number),
                       cat("column count changes from ", std::to_string(lines.front().fields.size()), " to ",
                           std::to_string(n)));
    const std::size_t off = n - 12;
    if (off == 1 && !stamps_in.empty())
      throw InputError(at(file, line.number),
                       "the file carries its own stamps (13 columns); drop the stamps file");
    std::array<double, 12> m{};
    for (std::size_t i = 0; i < 12; ++i)
      m[i] = parseNumber(line.fields[off + i], file, line.number, "matrix entry");
    // Rows of R are m[0..2], m[4..6], m[8..10]; check R^T R = I loosely (files carry ~6 digits).
    double worst = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double dot = 0.0;
        for (int r = 0; r < 3; ++r) dot += m[4 * r + a] * m[4 * r + b];
        worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
      }
    if (worst > 1e-3)
      throw InputError(
          at(file, line.number),
          cat("the 3x3 block is not a rotation matrix (R^T R differs from I by ", fixed(worst, 6), ")"));
    tilt.add(m[10], line.number);
    StampedPose p;
    const std::size_t index = traj.size();
    if (off == 1)
      p.stamp = parseStamp(line.fields[0], file, line.number);
    else if (!stamps.empty()) {
      if (index >= stamps.size())
        throw InputError(at(file, line.number), cat("more poses than stamps in ", stamps_origin.string(),
                                                    " (", std::to_string(stamps.size()), ")"));
      p.stamp = stamps[index];
    } else
      p.stamp = static_cast<StampNs>(index) * kNsPerSec;  // no stamps: the index, in seconds
    p.pose = mrpt::math::TPose2D(m[3], m[7], std::atan2(m[4], m[0]));
    checkPosition(p, file, line.number);
    traj.push_back(p);
    checkIncreasing(traj, file, line.number);
  }
  if (traj.empty()) throw InputError(file.string(), "no poses in file");
  if (!stamps.empty() && lines.front().fields.size() == 12 && stamps.size() != traj.size())
    throw InputError(stamps_origin.string(), cat(std::to_string(stamps.size()), " stamps for ",
                                                 std::to_string(traj.size()), " poses in ", file.string()));
  tilt.report(file);
  return traj;
}

Trajectory readTrajectoryFile(const fs::path& file, const TrajectoryReadOptions& options) {
  TrajectoryFormat format = options.format;
  if (format == TrajectoryFormat::Auto) format = detectTrajectoryFormat(file);
  if (format == TrajectoryFormat::Tum) {
    if (options.stamps_file)
      throw InputError(options.stamps_file->string(), "a stamps file only applies to KITTI trajectories");
    return readTumTrajectory(file);
  }
  return readKittiTrajectory(
      file, options.stamps_file ? readStampFile(*options.stamps_file) : std::vector<StampNs>{});
}

void writeTumTrajectory(const fs::path& file, const Trajectory& trajectory) {
  std::string text = "# t[s] x[m] y[m] z[m] qx qy qz qw (radarslam, SE(2): z = 0, rotation about z)\n";
  for (const auto& p : trajectory) {
    text.append(formatStampSeconds(p.stamp)).append(" ");
    text.append(fixed(p.pose.x, 6)).append(" ").append(fixed(p.pose.y, 6)).append(" 0 0 0 ");
    text.append(fixed(std::sin(p.pose.phi / 2), 9)).append(" ").append(fixed(std::cos(p.pose.phi / 2), 9));
    text.append("\n");
  }
  writeTextAtomically(file, text);
}

void writeKittiTrajectory(const fs::path& file, const Trajectory& trajectory) {
  std::string poses, stamps;
  for (const auto& p : trajectory) {
    const std::string c = fixed(std::cos(p.pose.phi), 9), s = fixed(std::sin(p.pose.phi), 9);
    const std::string ms = fixed(-std::sin(p.pose.phi), 9);
    poses.append(c).append(" ").append(ms).append(" 0 ").append(fixed(p.pose.x, 6)).append(" ");
    poses.append(s).append(" ").append(c).append(" 0 ").append(fixed(p.pose.y, 6)).append(" 0 0 1 0\n");
    stamps.append(formatStampSeconds(p.stamp)).append("\n");
  }
  writeTextAtomically(kittiStampsCompanion(file), stamps);
  writeTextAtomically(file, poses);
}

}  // namespace radarslam
