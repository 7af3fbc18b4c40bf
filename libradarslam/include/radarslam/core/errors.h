#pragma once
// One error type for every input we cannot use (a file, a config key, an argument).
// what() is a single line "<where>: <problem>" so programs can print it as-is and exit non-zero.
#include <cstddef>
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

namespace radarslam {

class InputError : public std::runtime_error {
 public:
  /// what() is oneLine(where) + ": " + oneLine(problem): whatever a file contained (a 20 MB line,
  /// control characters, bytes that are not UTF-8), the message stays one readable line.
  InputError(std::string where, std::string problem);
  const std::string& where() const noexcept { return where_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string where_;
  std::string problem_;
};

/// `text` as one printable line: control characters and bytes that are not valid UTF-8 become
/// escapes (\n, \t, \xNN); past `max_bytes` it is cut at a character boundary and
/// "... (N more bytes)" is appended.
std::string oneLine(std::string_view text, std::size_t max_bytes = 400);

/// The one-line message a program prints for an exception that escaped a command: InputError as
/// is; std::bad_alloc as an out-of-memory message; any other exception's first line (an OpenCV
/// "error: (-215:Assertion failed) ..." keeps only its message), passed through oneLine().
std::string describeException(const std::exception& e);

}  // namespace radarslam
