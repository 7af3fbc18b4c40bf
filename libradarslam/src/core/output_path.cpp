#include "radarslam/core/output_path.h"

#include <unistd.h>

#include <algorithm>

#include "radarslam/core/errors.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {

fs::path withoutTrailingSlash(const fs::path& p) { return p.has_filename() ? p : p.parent_path(); }

/// A missing output is created: its first existing ancestor must be a directory we may write in.
void checkCreatable(const fs::path& shown, const fs::path& path) {
  std::error_code ec;
  fs::path ancestor = fs::absolute(path, ec).parent_path();
  while (!ancestor.empty() && !fs::exists(fs::symlink_status(ancestor, ec)) &&
         ancestor != ancestor.root_path())
    ancestor = ancestor.parent_path();
  if (ancestor.empty()) return;
  if (!fs::is_directory(ancestor, ec))
    throw InputError(shown.string(), "cannot create it: " + ancestor.string() + " is not a directory");
  if (::access(ancestor.c_str(), W_OK | X_OK) != 0)
    throw InputError(shown.string(), "cannot create it: no write permission in " + ancestor.string());
}

/// Absolute, symbolic links resolved as far as the path exists.
fs::path canonicalAsFarAsPossible(const fs::path& p) {
  std::error_code ec;
  const fs::path abs = fs::absolute(withoutTrailingSlash(p), ec);
  fs::path c = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : c;
}

/// True if `inner` is `outer` or lies inside it (component-wise).
bool within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin(), o = outer.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing "" component
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

fs::path followSymlinks(const fs::path& path) {
  fs::path p = withoutTrailingSlash(path);
  for (int depth = 0; depth < 40; ++depth) {
    std::error_code ec;
    if (!fs::is_symlink(p, ec)) return p;
    const fs::path target = fs::read_symlink(p, ec);
    if (ec) return p;
    p = target.is_absolute() ? target : p.parent_path() / target;
    p = withoutTrailingSlash(p);
  }
  throw InputError(path.string(), "too many levels of symbolic links");
}

bool isSpecialFile(const fs::path& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  return !ec && (fs::is_character_file(st) || fs::is_block_file(st) || fs::is_fifo(st) || fs::is_socket(st));
}

void checkFileOutput(const fs::path& path, const std::string& option) {
  if (path.empty()) throw InputError(option, "empty output path");
  if (!path.has_filename()) throw InputError(path.string(), "expected a file name, not a directory");
  const fs::path p = followSymlinks(path);
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (fs::is_directory(st)) throw InputError(path.string(), "is a directory, expected a file name");
  if (!fs::exists(st)) checkCreatable(path, p);
}

void checkMapOutput(const fs::path& dir, bool force, const std::string& option) {
  if (dir.empty()) throw InputError(option, "empty output path");
  const fs::path d = followSymlinks(dir);
  std::error_code ec;
  const fs::file_status st = fs::status(d, ec);
  if (!fs::exists(st)) return checkCreatable(dir, d);
  if (fs::is_directory(st)) {
    if (fs::is_regular_file(d / "manifest.yaml", ec)) return;  // a map: replaced
    if (!fs::is_empty(d, ec))
      throw InputError(dir.string(),
                       "is a directory but not a radarslam map (no manifest.yaml): refusing to replace it");
    if (force) return;
    throw InputError(dir.string(), "is an empty directory, not a map (--force replaces it)");
  }
  if (fs::is_regular_file(st)) {
    if (force) return;
    throw InputError(dir.string(), "is a file, not a map directory (--force replaces it)");
  }
  throw InputError(dir.string(), "is a special file, not a map directory");
}

void checkDirectoryOutput(const fs::path& dir, const std::string& option) {
  if (dir.empty()) throw InputError(option, "empty output path");
  const fs::path d = followSymlinks(dir);
  std::error_code ec;
  const fs::file_status st = fs::status(d, ec);
  if (!fs::exists(st)) return checkCreatable(dir, d);
  if (!fs::is_directory(st)) throw InputError(dir.string(), "exists and is not a directory");
}

void checkNoOverlap(const fs::path& input, const fs::path& output, bool allow_inside) {
  if (input.empty() || output.empty()) return;
  const fs::path in = canonicalAsFarAsPossible(input), out = canonicalAsFarAsPossible(output);
  if (in == out) throw InputError(output.string(), "is the input " + input.string());
  if (within(in, out)) throw InputError(output.string(), "contains the input " + input.string());
  if (!allow_inside && within(out, in))
    throw InputError(output.string(), "is inside the input " + input.string());
}

void checkDistinctOutputs(const fs::path& first, const fs::path& second, const std::string& option) {
  if (canonicalAsFarAsPossible(followSymlinks(first)) == canonicalAsFarAsPossible(followSymlinks(second)))
    throw InputError(second.string(), option + " names the same file as " + first.string());
}

fs::path stagingSibling(const fs::path& path, const std::string& tag) {
  const fs::path p = withoutTrailingSlash(path);
  std::string name(1, '.');
  name.append(p.filename().string()).append(".").append(tag).append(".").append(std::to_string(::getpid()));
  return (p.has_parent_path() ? p.parent_path() : fs::path(".")) / name;
}

}  // namespace radarslam
