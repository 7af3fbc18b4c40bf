#include "radarslam/core/errors.h"

#include <utility>

namespace radarslam {

InputError::InputError(std::string where, std::string problem)
    : std::runtime_error(where + ": " + problem), where_(std::move(where)), problem_(std::move(problem)) {}

}  // namespace radarslam
