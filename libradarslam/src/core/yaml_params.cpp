#include "radarslam/core/yaml_params.h"

#include <mrpt/containers/yaml.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "radarslam/core/errors.h"

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

YamlParams YamlParams::fromText(const std::string& text, const std::string& origin) {
  YamlParams p;
  p.impl_->origin = origin;
  try {
    p.impl_->doc = mrpt::containers::yaml::FromText(text);
  } catch (const std::exception& e) {
    std::string msg = e.what();
    msg = trim(msg.substr(0, msg.find('\n')));
    throw InputError(origin, "invalid YAML: " + msg);
  }
  if (!p.impl_->doc.isNullNode() && !p.impl_->doc.isMap())
    throw InputError(origin, "expected a YAML map of parameters at the top level");
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

void YamlParams::rejectUnknownKeys() const {
  for (const auto& k : impl_->all)
    if (!impl_->used.count(k)) throw InputError(impl_->origin, "unknown parameter '" + k + "' (typo?)");
}

}  // namespace radarslam
