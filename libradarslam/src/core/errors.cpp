#include "radarslam/core/errors.h"

#include <cstdio>
#include <new>
#include <utility>

namespace radarslam {

namespace {
// Length of the valid UTF-8 sequence starting at s[i] (1 for ASCII), or 0 if it is not valid.
std::size_t utf8Length(std::string_view s, std::size_t i) {
  const auto b = static_cast<unsigned char>(s[i]);
  if (b < 0x80) return 1;
  std::size_t n = 0;
  unsigned min = 0;
  if ((b & 0xe0) == 0xc0)
    n = 2, min = 0x80;
  else if ((b & 0xf0) == 0xe0)
    n = 3, min = 0x800;
  else if ((b & 0xf8) == 0xf0)
    n = 4, min = 0x10000;
  else
    return 0;
  if (i + n > s.size()) return 0;
  unsigned cp = b & (0x7f >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const auto c = static_cast<unsigned char>(s[i + k]);
    if ((c & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (c & 0x3f);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n;
}

void appendEscaped(std::string& out, unsigned char b) {
  switch (b) {
    case '\n':
      out += "\\n";
      return;
    case '\r':
      out += "\\r";
      return;
    case '\t':
      out += "\\t";
      return;
    default: {
      char buf[5];
      std::snprintf(buf, sizeof(buf), "\\x%02x", b);
      out += buf;
    }
  }
}
}  // namespace

std::string oneLine(std::string_view text, std::size_t max_bytes) {
  std::string out;
  out.reserve(text.size() < max_bytes ? text.size() : max_bytes);
  std::size_t i = 0;
  while (i < text.size() && out.size() < max_bytes) {
    const auto b = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8Length(text, i);
    if (n == 0 || b < 0x20 || b == 0x7f) {
      appendEscaped(out, b);
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size() - i) + " more bytes)";
  return out;
}

InputError::InputError(std::string where, std::string problem)
    : std::runtime_error(oneLine(where, 600) + ": " + oneLine(problem)),
      where_(std::move(where)),
      problem_(std::move(problem)) {}

std::string describeException(const std::exception& e) {
  if (dynamic_cast<const InputError*>(&e) != nullptr) return e.what();
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr)
    return "out of memory (an input or parameter asks for more memory than this machine has)";
  std::string_view what = e.what();
  what = what.substr(0, what.find('\n'));
  // OpenCV: "OpenCV(4.6.0) /path/file.cpp:123: error: (-215:Assertion failed) cond in function 'f'"
  if (what.rfind("OpenCV(", 0) == 0) {
    const auto at = what.find(" error: ");
    if (at != std::string_view::npos) return "internal error in OpenCV: " + oneLine(what.substr(at + 8));
  }
  return oneLine(what);
}

}  // namespace radarslam
