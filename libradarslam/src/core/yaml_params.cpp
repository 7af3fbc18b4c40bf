#include "radarslam/core/yaml_params.h"

#include <mrpt/containers/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_text_check.h"
#include "stderr_capture.h"

namespace radarslam {

using Node = mrpt::containers::yaml::node_t;

struct YamlParams::Impl {
  std::string origin;
  mrpt::containers::yaml doc;
  std::set<std::string> used;
  std::set<std::string> all;  // every leaf key, dotted
};

namespace {
const Node& asNode(const std::shared_ptr<void>& p) { return *static_cast<const Node*>(p.get()); }

void collectKeys(const Node& n, const std::string& prefix, std::set<std::string>& out) {
  if (!n.isMap()) return;
  for (const auto& [k, v] : n.asMap()) {
    const std::string key = prefix + k.as<std::string>();
    if (v.isMap() && !v.asMap().empty())
      collectKeys(v, key + ".", out);
    else
      out.insert(key);
  }
}

const Node* child(const Node& n, const std::string& key) {
  if (!n.isMap()) return nullptr;
  for (const auto& [k, v] : n.asMap())
    if (k.as<std::string>() == key) return &v;
  return nullptr;
}

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
}  // namespace

YamlParams::YamlParams() : impl_(std::make_shared<Impl>()) {
  impl_->origin = "<defaults>";
  node_ = std::shared_ptr<void>(impl_, &impl_->doc.node());
}
YamlParams::~YamlParams() = default;
YamlParams::YamlParams(const YamlParams&) = default;
YamlParams& YamlParams::operator=(const YamlParams&) = default;

namespace {
/// The first libfyaml diagnostic ("<memory-@...>:3:1: error: flow sequence without a closing
/// bracket") as "line 3, column 1: flow sequence without a closing bracket", or "".
std::string parserDiagnostic(const std::string& output) {
  static const std::regex kDiag(R"(:(\d+):(\d+): error: ([^\n]*))");
  std::smatch m;
  if (!std::regex_search(output, m, kDiag)) return {};
  return "line " + m[1].str() + ", column " + m[2].str() + ": " + trim(m[3].str());
}

/// True if the text has anything but whitespace and comments.
bool hasContent(const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const std::string t = trim(line);
    if (!t.empty() && t[0] != '#' && t != "---" && t != "...") return true;
  }
  return false;
}
}  // namespace

YamlParams YamlParams::fromText(const std::string& text_in, const std::string& origin) {
  // A UTF-8 byte order mark is allowed (editors write it) and dropped.
  const std::string text = text_in.rfind("\xEF\xBB\xBF", 0) == 0 ? text_in.substr(3) : text_in;
  checkYamlText(text, origin);
  YamlParams p;
  p.impl_->origin = origin;
  const detail::Captured parsed =
      detail::captureStderr([&] { p.impl_->doc = mrpt::containers::yaml::FromText(text); });
  if (const std::string diag = parserDiagnostic(parsed.output); !diag.empty())
    throw InputError(origin, "invalid YAML at " + diag);
  if (parsed.error) {
    try {
      std::rethrow_exception(parsed.error);
    } catch (const std::exception& e) {
      std::string msg = e.what();
      const auto m = msg.find("Message:");
      msg = m == std::string::npos ? msg : msg.substr(m + 8);
      throw InputError(origin, "invalid YAML: " + trim(msg.substr(0, msg.find('\n'))));
    }
  }
  if (!parsed.output.empty()) std::fputs(parsed.output.c_str(), stderr);  // not the parser's
  const bool empty = p.impl_->doc.isNullNode() && !hasContent(text);
  if (!empty && !p.impl_->doc.isMap())
    throw InputError(origin, "expected a YAML map of parameters at the top level, got " +
                                 std::string(p.impl_->doc.isSequence() ? "a list" : "a single value"));
  p.node_ = std::shared_ptr<void>(p.impl_, &p.impl_->doc.node());
  collectKeys(p.impl_->doc.node(), "", p.impl_->all);
  return p;
}

YamlParams YamlParams::fromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, std::filesystem::exists(path) ? "cannot read file" : "file not found");
  std::stringstream ss;
  ss << in.rdbuf();
  return fromText(ss.str(), path);
}

const std::string& YamlParams::origin() const { return impl_->origin; }

bool YamlParams::has(const std::string& key) const { return child(asNode(node_), key) != nullptr; }

void YamlParams::markUsed(const std::string& key) const { impl_->used.insert(prefix_ + key); }

YamlParams YamlParams::section(const std::string& key) const {
  YamlParams s = *this;
  s.prefix_ = prefix_ + key + ".";
  const Node* c = child(asNode(node_), key);
  if (c == nullptr) {
    static const Node kEmpty;
    s.node_ = std::shared_ptr<void>(std::shared_ptr<void>(), const_cast<Node*>(&kEmpty));
    return s;
  }
  if (!c->isMap() && !c->isNullNode())
    throw InputError(impl_->origin, "key '" + prefix_ + key + "' must be a map of parameters");
  s.node_ = std::shared_ptr<void>(impl_, const_cast<Node*>(c));
  // Mark every leaf under an empty section as used; non-empty ones are checked leaf by leaf.
  if (c->isNullNode() || c->asMap().empty()) markUsed(key);
  return s;
}

std::string YamlParams::scalarText(const std::string& key) const {
  const Node* c = child(asNode(node_), key);
  if (!c->isScalar()) throw InputError(impl_->origin, "key '" + prefix_ + key + "' must be a single value");
  return trim(c->as<std::string>());
}

namespace {
[[noreturn]] void badValue(const std::string& origin, const std::string& key, const std::string& text,
                           const char* expected) {
  throw InputError(origin, "key '" + key + "': expected " + expected + ", got '" + text + "'");
}
}  // namespace

void YamlParams::get(const std::string& key, double& value) const {
  if (!has(key)) return;
  const std::string t = scalarText(key);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || errno != 0) badValue(impl_->origin, prefix_ + key, t, "a number");
  value = v;
  markUsed(key);
}

void YamlParams::get(const std::string& key, float& value) const {
  double d = value;
  get(key, d);
  value = static_cast<float>(d);
}

void YamlParams::get(const std::string& key, int& value) const {
  if (!has(key)) return;
  const std::string t = scalarText(key);
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (t.empty() || *end != '\0' || errno != 0 || v < INT32_MIN || v > INT32_MAX)
    badValue(impl_->origin, prefix_ + key, t, "an integer");
  value = static_cast<int>(v);
  markUsed(key);
}

void YamlParams::get(const std::string& key, unsigned& value) const {
  int v = static_cast<int>(value);
  if (!has(key)) return;
  get(key, v);
  if (v < 0) badValue(impl_->origin, prefix_ + key, std::to_string(v), "a non-negative integer");
  value = static_cast<unsigned>(v);
}

void YamlParams::get(const std::string& key, bool& value) const {
  if (!has(key)) return;
  const std::string t = scalarText(key);
  if (t == "true" || t == "True" || t == "yes" || t == "on" || t == "1")
    value = true;
  else if (t == "false" || t == "False" || t == "no" || t == "off" || t == "0")
    value = false;
  else
    badValue(impl_->origin, prefix_ + key, t, "true or false");
  markUsed(key);
}

void YamlParams::get(const std::string& key, std::string& value) const {
  if (!has(key)) return;
  value = scalarText(key);
  markUsed(key);
}

void YamlParams::get(const std::string& key, std::vector<double>& value) const {
  if (!has(key)) return;
  const Node* c = child(asNode(node_), key);
  if (!c->isSequence()) throw InputError(impl_->origin, "key '" + prefix_ + key + "' must be a list");
  std::vector<double> out;
  for (const auto& item : c->asSequence()) {
    const std::string t = trim(item.as<std::string>());
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') badValue(impl_->origin, prefix_ + key, t, "a list of numbers");
    out.push_back(v);
  }
  value = std::move(out);
  markUsed(key);
}

namespace {
std::string number(double v) {
  std::ostringstream os;
  os.precision(12);
  os << v;
  return os.str();
}
}  // namespace

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::text() const {
  return (lo_open ? "(" : "[") + number(lo) + ", " + number(hi) + (hi_open ? ")" : "]");
}

void YamlParams::fail(const std::string& key, const std::string& problem) const {
  throw InputError(impl_->origin, "key '" + prefix_ + key + "': " + problem);
}

void YamlParams::check(const std::string& key, double value, const Range& range) const {
  if (!range.contains(value)) fail(key, number(value) + " is out of range " + range.text());
}

void YamlParams::get(const std::string& key, double& value, const Range& range) const {
  if (!has(key)) return;
  double v = value;
  get(key, v);
  check(key, v, range);
  value = v;
}

void YamlParams::get(const std::string& key, float& value, const Range& range) const {
  double v = value;
  get(key, v, range);
  value = static_cast<float>(v);
}

void YamlParams::get(const std::string& key, int& value, const Range& range) const {
  if (!has(key)) return;
  // Read as a number first so that "1e9" is reported as out of range, not as a bad integer.
  double d = value;
  get(key, d);
  check(key, d, range);
  if (d != std::floor(d)) fail(key, "expected an integer, got " + number(d));
  value = static_cast<int>(d);
}

void YamlParams::get(const std::string& key, unsigned& value, const Range& range) const {
  int v = static_cast<int>(value);
  get(key, v, range);
  if (v < 0) fail(key, "expected a non-negative integer");
  value = static_cast<unsigned>(v);
}

void YamlParams::get(const std::string& key, long& value, const Range& range) const {
  if (!has(key)) return;
  double d = static_cast<double>(value);  // exact for integers up to 2^53
  get(key, d);
  check(key, d, range);
  if (d != std::floor(d) || std::abs(d) > 9007199254740992.0)
    fail(key, "expected an integer, got " + number(d));
  value = static_cast<long>(d);
}

void YamlParams::get(const std::string& key, std::size_t& value, const Range& range) const {
  long v = static_cast<long>(value);  // 64-bit: sizes beyond 2^31 (e.g. cells of a city grid)
  get(key, v, range);
  if (v < 0) fail(key, "expected a non-negative integer");
  value = static_cast<std::size_t>(v);
}

void YamlParams::get(const std::string& key, std::vector<double>& value, const Range& range,
                     std::size_t max_items) const {
  if (!has(key)) return;
  std::vector<double> v;
  get(key, v);
  if (v.size() > max_items) fail(key, "more than " + std::to_string(max_items) + " values");
  for (double x : v)
    if (!range.contains(x)) fail(key, number(x) + " is out of range " + range.text());
  value = std::move(v);
}

void YamlParams::rejectUnknownKeys() const {
  for (const auto& k : impl_->all)
    if (!impl_->used.count(k)) throw InputError(impl_->origin, "unknown parameter '" + k + "' (typo?)");
}

}  // namespace radarslam
