#include "text_util.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"

namespace radarslam::io_detail {

std::ifstream openText(const std::filesystem::path& path, const char* what) {
  requireRegularFile(path, (std::string("cannot open ") + what).c_str());
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), std::string("cannot open ") + what);
  return in;
}

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> split(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const auto pos = line.find(sep, start);
    out.push_back(
        trim(line.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start)));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return out;
}

std::string lineWhere(const std::filesystem::path& file, std::size_t line_no) {
  std::string s = file.string();
  s.append(":").append(std::to_string(line_no));
  return s;
}

double parseDouble(std::string_view text, const std::string& where, const char* field) {
  const std::string s(text);
  char* end = nullptr;
  errno = 0;
  const double v = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
    throw InputError(where, std::string(field) + " is not a finite number: '" + s + "'");
  return v;
}

std::int64_t parseInt(std::string_view text, const std::string& where, const char* field) {
  std::int64_t v = 0;
  const auto* first = text.data();
  const auto* last = text.data() + text.size();
  if (!text.empty() && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (text.empty() || ec != std::errc() || ptr != last)
    throw InputError(where, std::string(field) + " is not an integer: '" + std::string(text) + "'");
  return v;
}

StampNs parseMicroseconds(std::string_view text, const std::string& where, const char* field) {
  const std::int64_t us = parseInt(text, where, field);
  constexpr std::int64_t kMaxUs = std::numeric_limits<StampNs>::max() / kNsPerUs;
  if (us > kMaxUs || us < -kMaxUs)
    throw InputError(where, std::string(field) + " is out of range for a time in microseconds: '" +
                                std::string(text) + "'");
  return us * kNsPerUs;
}

StampNs parseStamp(std::string_view text, const std::string& where, const char* field) {
  StampNs t = 0;
  if (!parseStampByDigits(std::string(text), t))
    throw InputError(where, std::string(field) + " is not a UNIX timestamp: '" + std::string(text) + "'");
  return t;
}

std::vector<unsigned char> readBytes(const std::filesystem::path& path) {
  requireRegularFile(path, "cannot open file (missing or unreadable)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot open file (missing or unreadable)");
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size < 0) throw InputError(path.string(), "cannot determine the file size");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!bytes.empty() && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw InputError(path.string(), "read error");
  return bytes;
}

}  // namespace radarslam::io_detail
