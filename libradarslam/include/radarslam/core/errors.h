#pragma once
// One error type for every input we cannot use (a file, a config key, an argument).
// what() is a single line "<where>: <problem>" so programs can print it as-is and exit non-zero.
#include <stdexcept>
#include <string>

namespace radarslam {

class InputError : public std::runtime_error {
 public:
  InputError(std::string where, std::string problem);
  const std::string& where() const noexcept { return where_; }
  const std::string& problem() const noexcept { return problem_; }

 private:
  std::string where_;
  std::string problem_;
};

}  // namespace radarslam
