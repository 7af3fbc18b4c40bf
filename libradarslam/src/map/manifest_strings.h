#pragma once
// Free-text strings of the map manifest (source_dataset, software_version): written as YAML
// double-quoted scalars that read back byte for byte, with a hex twin for the strings YAML cannot
// carry (not UTF-8, or with leading/trailing whitespace, which YamlParams trims). maps/README.md.
#include <optional>
#include <string>

namespace radarslam::mapcodec {

/// `s` as a YAML double-quoted scalar in pure ASCII: `"` and `\` escaped, control characters as
/// \xNN, other code points as \uNNNN / \UNNNNNNNN; a byte that is not part of valid UTF-8 becomes
/// \uFFFD (lossy: see needsHexTwin).
std::string yamlQuoted(const std::string& s);

/// True if yamlQuoted(s) does not read back as exactly `s` through YamlParams.
bool needsHexTwin(const std::string& s);

/// `v` with 17 significant digits: reads back as the same double.
std::string exactDouble(double v);

std::string hexEncode(const std::string& bytes);
/// nullopt unless `hex` is an even number of hex digits.
std::optional<std::string> hexDecode(const std::string& hex);

}  // namespace radarslam::mapcodec
