#include "radarslam/core/yaml_text_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "radarslam/core/errors.h"

namespace radarslam {

namespace {

/// Length of the UTF-8 sequence starting at text[i], or 0 if it is not a valid one.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto b = static_cast<std::uint8_t>(text[i]);
  std::size_t n = 0;
  std::uint32_t cp = 0;
  if (b < 0x80) return 1;
  if (b >= 0xC2 && b <= 0xDF) {
    n = 2;
    cp = b & 0x1Fu;
  } else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
    cp = b & 0x0Fu;
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
    cp = b & 0x07u;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const auto c = static_cast<std::uint8_t>(text[i + k]);
    if ((c & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (c & 0x3Fu);
  }
  const bool overlong = (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000);
  const bool surrogate = cp >= 0xD800 && cp <= 0xDFFF;
  if (overlong || surrogate || cp > 0x10FFFF) return 0;
  return n;
}

}  // namespace

std::size_t yamlNestingDepth(std::string_view text, std::size_t stop_above) {
  std::vector<std::size_t> indents;  // block indentation levels enclosing the current line
  std::size_t flow = 0, deepest = 0;
  char quote = 0;  // inside a '...' or "..." scalar (may span lines)
  std::size_t i = 0;
  while (i < text.size()) {
    // Start of a line.
    std::size_t depth_here = 0;
    if (flow == 0 && quote == 0) {
      std::size_t indent = 0;
      while (i + indent < text.size() && (text[i + indent] == ' ' || text[i + indent] == '\t')) ++indent;
      const std::size_t first = i + indent;
      const bool blank =
          first >= text.size() || text[first] == '\n' || text[first] == '\r' || text[first] == '#';
      if (!blank) {
        while (!indents.empty() && indents.back() >= indent) indents.pop_back();
        indents.push_back(indent);
        depth_here = indents.size();
        // "- - - x": every leading sequence indicator is one more level.
        std::size_t j = first;
        while (j < text.size() && text[j] == '-' &&
               (j + 1 == text.size() || text[j + 1] == ' ' || text[j + 1] == '\n')) {
          ++depth_here;
          j += 1;
          while (j < text.size() && text[j] == ' ') ++j;
        }
      }
      i = first;
    } else {
      depth_here = indents.size();
    }
    deepest = std::max(deepest, depth_here + flow);
    if (deepest > stop_above) return deepest;
    // The rest of the line. `boundary`: the next character may start a token (a quote or a
    // flow collection); inside a plain scalar ("x[1]", "it's") brackets and quotes are text.
    bool boundary = true;
    for (; i < text.size() && text[i] != '\n'; ++i) {
      const char c = text[i];
      if (quote != 0) {
        if (c == '\\' && quote == '"' && i + 1 < text.size() && text[i + 1] != '\n')
          ++i;
        else if (c == quote)
          quote = 0;
        continue;
      }
      const bool space = c == ' ' || c == '\t';
      if (c == '#' && boundary &&
          (space || i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n')) {
        while (i < text.size() && text[i] != '\n') ++i;
        break;
      }
      bool opened = false;
      if ((c == '\'' || c == '"') && boundary) {
        quote = c;
      } else if ((c == '[' || c == '{') && boundary) {
        ++flow;
        opened = true;
        deepest = std::max(deepest, depth_here + flow);
        if (deepest > stop_above) return deepest;
      } else if ((c == ']' || c == '}') && flow > 0) {
        --flow;
      }
      boundary = space || opened || c == ',' || c == ':' || c == '-' || c == '?';
    }
    if (i < text.size()) ++i;  // the '\n'
  }
  return deepest;
}

std::string yamlTextProblem(std::string_view text) {
  // NUL bytes first: they mark a binary file wherever they are (a PNG's first byte is not UTF-8).
  if (const auto nul = text.find('\0'); nul != std::string_view::npos)
    return "contains a NUL byte at line " +
           std::to_string(1 +
                          std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n')) +
           " (binary file?)";
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto b = static_cast<std::uint8_t>(text[i]);
    if (b == '\n') {
      ++line;
      ++i;
      continue;
    }
    if ((b < 0x20 && b != '\t' && b != '\r') || b == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned>(b));
      return std::string("contains the control byte ") + hex + " at line " + std::to_string(line) +
             " (binary file?)";
    }
    const std::size_t n = utf8Length(text, i);
    if (n == 0) return "is not valid UTF-8 text (line " + std::to_string(line) + "; binary file?)";
    i += n;
  }
  return {};
}

void checkYamlText(std::string_view text, const std::string& origin) {
  if (const std::string problem = yamlTextProblem(text); !problem.empty()) throw InputError(origin, problem);
  if (yamlNestingDepth(text) > kMaxYamlDepth)
    throw InputError(origin, "YAML nested more than " + std::to_string(kMaxYamlDepth) + " levels deep");
}

}  // namespace radarslam
