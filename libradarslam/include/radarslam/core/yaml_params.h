#pragma once
// Parameters live in plain structs with defaults; YAML files only override them. YamlParams
// reads one section of a YAML file, type-checks each value and remembers which keys were used,
// so that a typo in a config ("keyframe_distnace") is an error naming the file and the key
// instead of a silently ignored setting.
#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace radarslam {

/// The valid values of a numeric parameter: [lo, hi], with either end optionally open. NaN is
/// never in range. Every range-checked get() states one next to its key, so that the accepted
/// values are documented where the parameter is read (and listed in docs/parameters.md).
struct Range {
  double lo = 0.0;
  double hi = 0.0;
  bool lo_open = false;
  bool hi_open = false;

  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  /// (lo, hi]: e.g. Range::above(0, 100) for "positive, at most 100".
  static Range above(double lo, double hi) { return {lo, hi, true, false}; }
  bool contains(double v) const;
  /// "[lo, hi]", "(lo, hi]", ...
  std::string text() const;
};

class YamlParams {
 public:
  /// An empty parameter set (every get() keeps its default).
  YamlParams();
  /// Throws InputError(path, ...) if the file is missing or not valid YAML.
  static YamlParams fromFile(const std::string& path);
  static YamlParams fromText(const std::string& text, const std::string& origin = "<text>");
  ~YamlParams();
  YamlParams(const YamlParams&);
  YamlParams& operator=(const YamlParams&);

  bool has(const std::string& key) const;
  /// The sub-map `key` (empty if absent). Throws InputError if `key` exists and is not a map.
  YamlParams section(const std::string& key) const;

  /// Overrides `value` if `key` is present. Throws InputError naming the file and the key if the
  /// value does not parse as the requested type.
  void get(const std::string& key, double& value) const;
  void get(const std::string& key, float& value) const;
  void get(const std::string& key, int& value) const;
  void get(const std::string& key, unsigned& value) const;
  void get(const std::string& key, bool& value) const;
  void get(const std::string& key, std::string& value) const;
  void get(const std::string& key, std::vector<double>& value) const;

  /// As above, and throws InputError naming the file and the key if the value read is outside
  /// `range`. Absent keys keep the default (which the caller's range must contain).
  void get(const std::string& key, double& value, const Range& range) const;
  void get(const std::string& key, float& value, const Range& range) const;
  void get(const std::string& key, int& value, const Range& range) const;
  void get(const std::string& key, unsigned& value, const Range& range) const;
  void get(const std::string& key, long& value, const Range& range) const;
  void get(const std::string& key, std::size_t& value, const Range& range) const;
  /// A list of at most `max_items` numbers, each in `range`.
  void get(const std::string& key, std::vector<double>& value, const Range& range,
           std::size_t max_items) const;

  /// Throws InputError(origin, "key '<section.key>': <problem>") (for cross-field checks).
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  /// fail()s unless `value` (of `key`, whether read or default) lies in `range`.
  void check(const std::string& key, double value, const Range& range) const;

  /// Throws InputError naming the first key of this file that no get()/section() consumed.
  void rejectUnknownKeys() const;

  const std::string& origin() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;  // the parsed document, shared by all sections
  std::string prefix_;          // "frontend." for a section
  std::shared_ptr<void> node_;  // this section's node (mrpt yaml node), type-erased
  std::string scalarText(const std::string& key) const;
  void markUsed(const std::string& key) const;
};

}  // namespace radarslam
