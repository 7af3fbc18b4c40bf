#pragma once
// Checks a YAML text must pass before it reaches MRPT's parser. MRPT's parser is recursive
// descent: a file nested a few thousand levels deep (`x: [[[[...`, `{a: {a: ...`, or block
// indentation) overflows the stack, so the nesting depth is bounded here by a cheap linear
// pre-scan. Binary input (NUL bytes, control bytes, invalid UTF-8) is not YAML and is refused
// instead of being half-parsed into an empty document.
#include <cstddef>
#include <string>
#include <string_view>

namespace radarslam {

/// Deepest nesting a YAML config may have. Real configs need fewer than 10 levels.
inline constexpr std::size_t kMaxYamlDepth = 64;

/// An upper bound on the nesting depth of `text`: flow brackets `[`/`{` open outside quoted
/// strings and comments, plus the number of distinct block indentation levels enclosing a line,
/// plus "- " sequence entries at the start of a line. One linear pass; stops counting as soon
/// as the depth exceeds `stop_above` (and returns that depth).
std::size_t yamlNestingDepth(std::string_view text, std::size_t stop_above = kMaxYamlDepth);

/// Empty if `text` can be a YAML text; otherwise what is wrong ("contains a NUL byte at
/// line 3 (binary file?)", "is not valid UTF-8 text (line 1)", ...).
std::string yamlTextProblem(std::string_view text);

/// Throws InputError(origin, ...) if yamlTextProblem() finds something or the nesting is deeper
/// than kMaxYamlDepth.
void checkYamlText(std::string_view text, const std::string& origin);

}  // namespace radarslam
