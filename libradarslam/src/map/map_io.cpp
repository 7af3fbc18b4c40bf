// Map directory save/load (format: maps/README.md).
#include "radarslam/map/map_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "binary_codec.h"
#include "manifest_strings.h"
#include "map_validation.h"
#include "radarslam/core/atomic_file.h"
#include "radarslam/core/cleanup_on_signal.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "radarslam/core/log.h"
#include "radarslam/core/output_path.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/sha256.h"

namespace radarslam {
namespace fs = std::filesystem;
using mapcodec::Reader;
using mapcodec::Writer;

namespace {

constexpr char kKeyframesMagic[9] = "RSLMKEYF";
constexpr char kPointsMagic[9] = "RSLMPNTS";
constexpr char kGraphMagic[9] = "RSLMGRPH";

struct FileEntry {
  const char* key;   // key under `files:` in the manifest
  const char* name;  // file name in the map directory
};
constexpr FileEntry kFiles[] = {{"parameters", "parameters.yaml"},
                                {"keyframes", "keyframes.bin"},
                                {"points", "points.bin"},
                                {"graph", "graph.bin"}};

void fsyncDirectory(const fs::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// "maps/x/" -> "maps/x" (a trailing slash would make parent_path() the map itself).
fs::path withoutTrailingSlash(const fs::path& dir) { return dir.has_filename() ? dir : dir.parent_path(); }

fs::path parentOf(const fs::path& dir_in) {
  const fs::path dir = withoutTrailingSlash(dir_in);
  return dir.has_parent_path() ? dir.parent_path() : fs::path(".");
}

std::string siblingName(const fs::path& dir, const char* suffix) {
  const fs::path d = withoutTrailingSlash(dir);
  std::string name(1, '.');
  name.append(d.filename().string()).append(suffix);
  return name;
}

// --- encoding --------------------------------------------------------------------------------

std::string encodeKeyframes(const KeyframeMap& map) {
  Writer w;
  std::size_t total = mapcodec::kHeaderBytes;
  for (const auto& kf : map.keyframes) total += 48 + kf.points.size() * 12 + kf.descriptor.size() * 4;
  w.reserve(total);
  w.header(kKeyframesMagic, kMapFormatVersion, map.keyframes.size());
  for (const auto& kf : map.keyframes) {
    w.put<std::uint64_t>(kf.id);
    w.put<std::int64_t>(kf.stamp_ns);
    w.put<double>(kf.pose.x);
    w.put<double>(kf.pose.y);
    w.put<double>(kf.pose.phi);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(kf.points.size()));
    w.put<std::uint32_t>(static_cast<std::uint32_t>(kf.descriptor.size()));
    static_assert(sizeof(KeyframePoint) == 12);
    w.putRaw(kf.points.data(), kf.points.size() * sizeof(KeyframePoint));
    w.putRaw(kf.descriptor.data(), kf.descriptor.size() * sizeof(float));
  }
  return w.bytes();
}

std::string encodePoints(const KeyframeMap& map) {
  Writer w;
  w.header(kPointsMagic, kMapFormatVersion, map.points.size());
  for (const auto& p : map.points) {
    w.put<std::uint64_t>(p.id);
    w.put<double>(p.x);
    w.put<double>(p.y);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(p.observed_by.size()));
    w.putRaw(p.observed_by.data(), p.observed_by.size() * sizeof(std::uint64_t));
  }
  return w.bytes();
}

std::string encodeGraph(const KeyframeMap& map) {
  Writer w;
  w.header(kGraphMagic, kMapFormatVersion, map.edges.size());
  for (const auto& e : map.edges) {
    w.put<std::uint64_t>(e.from);
    w.put<std::uint64_t>(e.to);
    w.put<double>(e.relative.x);
    w.put<double>(e.relative.y);
    w.put<double>(e.relative.phi);
    for (double v : e.information) w.put<double>(v);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(e.kind));
  }
  return w.bytes();
}

// --- decoding --------------------------------------------------------------------------------

void expectEnd(const Reader& r) {
  if (r.remaining() != 0)
    throw InputError(r.file(),
                     std::to_string(r.remaining()) + " unexpected trailing bytes after the last record");
}

// A count read from a file must fit in what is left of it (guards huge allocations on garbage).
void checkFits(const Reader& r, std::uint64_t count, std::uint64_t bytes_each, const char* what) {
  if (bytes_each > 0 && count > r.remaining() / bytes_each)
    throw InputError(r.file(), std::string("truncated: ")
                                   .append(std::to_string(count))
                                   .append(" ")
                                   .append(what)
                                   .append(" announced but only ")
                                   .append(std::to_string(r.remaining()))
                                   .append(" bytes remain"));
}

void decodeKeyframes(const std::string& bytes, const std::string& file, KeyframeMap& map) {
  Reader r(bytes, file);
  const auto n = r.header(kKeyframesMagic, kMapFormatVersion);
  checkFits(r, n, 48, "keyframes");
  map.keyframes.resize(n);
  for (auto& kf : map.keyframes) {
    kf.id = r.get<std::uint64_t>("a keyframe id");
    kf.stamp_ns = r.get<std::int64_t>("a keyframe stamp");
    kf.pose.x = r.get<double>("a keyframe pose");
    kf.pose.y = r.get<double>("a keyframe pose");
    kf.pose.phi = r.get<double>("a keyframe pose");
    const auto np = r.get<std::uint32_t>("a keyframe point count");
    const auto nd = r.get<std::uint32_t>("a keyframe descriptor length");
    checkFits(r, np, sizeof(KeyframePoint), "keyframe points");
    kf.points.resize(np);
    r.getRaw(kf.points.data(), np * sizeof(KeyframePoint), "keyframe points");
    checkFits(r, nd, sizeof(float), "descriptor values");
    kf.descriptor.resize(nd);
    r.getRaw(kf.descriptor.data(), nd * sizeof(float), "a keyframe descriptor");
  }
  expectEnd(r);
}

void decodePoints(const std::string& bytes, const std::string& file, KeyframeMap& map) {
  Reader r(bytes, file);
  const auto n = r.header(kPointsMagic, kMapFormatVersion);
  checkFits(r, n, 28, "map points");
  map.points.resize(n);
  for (auto& p : map.points) {
    p.id = r.get<std::uint64_t>("a map point id");
    p.x = r.get<double>("a map point position");
    p.y = r.get<double>("a map point position");
    const auto no = r.get<std::uint32_t>("a map point observation count");
    checkFits(r, no, sizeof(std::uint64_t), "observing keyframe ids");
    p.observed_by.resize(no);
    r.getRaw(p.observed_by.data(), no * sizeof(std::uint64_t), "observing keyframe ids");
  }
  expectEnd(r);
}

void decodeGraph(const std::string& bytes, const std::string& file, KeyframeMap& map) {
  Reader r(bytes, file);
  const auto n = r.header(kGraphMagic, kMapFormatVersion);
  checkFits(r, n, 116, "edges");
  map.edges.resize(n);
  for (auto& e : map.edges) {
    e.from = r.get<std::uint64_t>("an edge");
    e.to = r.get<std::uint64_t>("an edge");
    e.relative.x = r.get<double>("an edge pose");
    e.relative.y = r.get<double>("an edge pose");
    e.relative.phi = r.get<double>("an edge pose");
    for (double& v : e.information) v = r.get<double>("an edge information matrix");
    const auto kind = r.get<std::uint32_t>("an edge kind");
    if (kind > 1) throw InputError(file, "unknown edge kind " + std::to_string(kind));
    e.kind = static_cast<EdgeKind>(kind);
  }
  expectEnd(r);
}

// --- manifest --------------------------------------------------------------------------------

std::string quoted(const std::string& s) { return mapcodec::yamlQuoted(s); }

// `key: "<escaped>"`, plus `key_hex: "<bytes>"` when YAML cannot carry the string exactly.
std::string stringEntry(const char* key, const std::string& value) {
  std::string out = std::string(key) + ": " + quoted(value) + "\n";
  if (mapcodec::needsHexTwin(value))
    out += std::string(key) + "_hex: " + quoted(mapcodec::hexEncode(value)) + "\n";
  return out;
}

// The manifest string `key`, from its hex twin if there is one.
void readString(const YamlParams& manifest, const std::string& mp, const std::string& key, std::string& out) {
  manifest.get(key, out);
  if (!manifest.has(key + "_hex")) return;
  std::string hex;
  manifest.get(key + "_hex", hex);
  const auto bytes = mapcodec::hexDecode(hex);
  if (!bytes) throw InputError(mp, key + "_hex: expected an even number of hex digits");
  out = *bytes;
}

std::string utcText(StampNs t) {
  const std::time_t secs = static_cast<std::time_t>(t / kNsPerSec);
  std::tm tm{};
  gmtime_r(&secs, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

struct WrittenFile {
  std::string key, name, sha256;
  std::size_t bytes = 0;
};

std::string manifestText(const KeyframeMap& map, StampNs created, const std::vector<WrittenFile>& files,
                         const std::optional<MapLayersManifest>& layers) {
  std::ostringstream m;
  m << "# radarslam map manifest (format: maps/README.md)\n"
    << "format_version: " << kMapFormatVersion << "\n"
    << "created_ns: " << created << "\n"
    << "created_utc: " << quoted(utcText(created)) << "\n"
    << stringEntry("software_version", map.meta.software_version)
    << stringEntry("source_dataset", map.meta.source_dataset)
    << "clouds_motion_compensated: " << (map.meta.clouds_motion_compensated ? "true" : "false") << "\n"
    << "sensor:\n"
    << "  num_azimuths: " << map.meta.sensor.num_azimuths << "\n"
    << "  num_bins: " << map.meta.sensor.num_bins << "\n"
    << "  range_resolution_m: " << mapcodec::exactDouble(map.meta.sensor.range_resolution_m) << "\n"
    << "  range_offset_m: " << mapcodec::exactDouble(map.meta.sensor.range_offset_m) << "\n"
    << "counts:\n"
    << "  keyframes: " << map.keyframes.size() << "\n"
    << "  points: " << map.points.size() << "\n"
    << "  edges: " << map.edges.size() << "\n"
    << "files:\n";
  for (const auto& f : files)
    m << "  " << f.key << ":\n"
      << "    name: " << quoted(f.name) << "\n"
      << "    bytes: " << f.bytes << "\n"
      << "    sha256: " << quoted(f.sha256) << "\n";
  if (layers) m << layersManifestText(*layers);
  return m.str();
}

void writeFileSynced(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw InputError(path.string(), "write failed (disk full or no permission?)");
  fsyncFile(path);
}

std::string readWholeFile(const fs::path& path) {
  requireRegularFile(path, "missing or unreadable map file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "missing or unreadable map file");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  in.seekg(0);
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (!in) throw InputError(path.string(), "read failed");
  return bytes;
}

std::uint64_t parseU64(const std::string& text, const std::string& where, const std::string& key) {
  try {
    std::size_t used = 0;
    const auto v = std::stoull(text, &used);
    if (used == text.size()) return v;
  } catch (const std::exception&) {
  }
  throw InputError(where, key + ": expected a non-negative integer, got '" + text + "'");
}

bool hasManifest(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "manifest.yaml", ec);
}

}  // namespace

fs::path mapTempDir(const fs::path& dir) { return parentOf(dir) / siblingName(dir, ".map-tmp"); }
fs::path mapBackupDir(const fs::path& dir) { return parentOf(dir) / siblingName(dir, ".map-backup"); }

fs::path resolveMapPath(const std::string& name_or_path) {
  if (name_or_path.empty()) throw InputError("map", "empty map name");
  const bool plain_name =
      name_or_path.find('/') == std::string::npos && name_or_path != "." && name_or_path != "..";
  if (!plain_name) return name_or_path;
  const fs::path local = fs::path("maps") / name_or_path;
  std::error_code ec;
  if (fs::exists(local, ec) || fs::exists(mapBackupDir(local), ec)) return local;
  if (const char* env = std::getenv("RADARSLAM_MAPS_DIR"); env != nullptr && *env != '\0')
    return fs::path(env) / name_or_path;
  return local;
}

void saveMap(const KeyframeMap& map, const fs::path& dir_in, const MapSaveHooks& hooks,
             const std::optional<MapLayerParams>& layer_params) {
  if (dir_in.empty()) throw InputError("map", "empty map directory path");
  // Through a symbolic link the map it points to is replaced, never the link.
  const fs::path dir = followSymlinks(dir_in);
  const fs::path parent = parentOf(dir);
  const fs::path tmp = mapTempDir(dir);
  const fs::path backup = mapBackupDir(dir);
  std::error_code ec;
  // Only a map is ever replaced: the contents of any other directory are never deleted.
  if (fs::is_directory(dir, ec) && !hasManifest(dir) && !fs::is_empty(dir, ec))
    throw InputError(dir_in.string(),
                     "is a directory but not a radarslam map (no manifest.yaml): refusing to replace it");
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec) && !fs::is_regular_file(dir, ec))
    throw InputError(dir_in.string(), "is a special file, not a map directory");
  fs::create_directories(parent, ec);
  if (ec) throw InputError(parent.string(), "cannot create directory: " + ec.message());
  fs::remove_all(tmp, ec);  // a stale temporary from an interrupted save
  const TemporaryPath removed_on_signal(tmp);
  if (!fs::create_directory(tmp, ec) || ec)
    throw InputError(tmp.string(), "cannot create temporary map directory: " + ec.message());

  try {
    const StampNs created = map.meta.created_ns != 0
                                ? map.meta.created_ns
                                : std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::system_clock::now().time_since_epoch())
                                      .count();
    std::vector<WrittenFile> files;
    for (const auto& entry : kFiles) {
      const std::string key = entry.key;
      const std::string bytes = key == "parameters"  ? map.meta.parameters_yaml
                                : key == "keyframes" ? encodeKeyframes(map)
                                : key == "points"    ? encodePoints(map)
                                                     : encodeGraph(map);
      writeFileSynced(tmp / entry.name, bytes);
      files.push_back({key, entry.name, sha256Hex(bytes), bytes.size()});
      if (hooks.after_file) hooks.after_file(entry.name);
    }
    std::optional<MapLayersManifest> layers;
    if (layer_params) {
      layers = writeMapLayers(map, tmp, *layer_params);
      if (hooks.after_file) hooks.after_file(kLayersDir);
    }
    writeFileSynced(tmp / "manifest.yaml", manifestText(map, created, files, layers));
    if (hooks.after_file) hooks.after_file("manifest.yaml");
    if (hooks.write_products) hooks.write_products(tmp);
    fsyncDirectory(tmp);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }

  // Swap into place. States a crash can leave: {old, tmp} -> old loads; {backup, tmp} -> loadMap
  // restores the backup; {new, backup} -> new loads, the next save removes the backup.
  if (fs::exists(backup, ec)) {
    if (hasManifest(dir)) {
      fs::remove_all(backup, ec);
    } else {  // only the backup is complete: restore it first so it is what we replace
      fs::remove_all(dir, ec);
      fs::rename(backup, dir, ec);
      if (ec) throw InputError(backup.string(), "cannot restore map backup: " + ec.message());
    }
  }
  const bool had_old = fs::exists(dir, ec);
  if (had_old) {
    fs::rename(dir, backup, ec);
    if (ec) {
      const std::string msg = ec.message();  // before remove_all() resets ec ("...: Success")
      fs::remove_all(tmp, ec);
      throw InputError(dir.string(), "cannot move the previous map aside: " + msg);
    }
  }
  fs::rename(tmp, dir, ec);
  if (ec) {
    const std::string msg = ec.message();
    if (had_old) fs::rename(backup, dir, ec);  // roll back
    throw InputError(dir.string(), "cannot move the new map into place: " + msg);
  }
  fsyncDirectory(parent);
  if (had_old) fs::remove_all(backup, ec);
}

MapManifestSummary readMapManifest(const fs::path& dir_in) {
  const fs::path manifest_path = withoutTrailingSlash(dir_in) / "manifest.yaml";
  const std::string mp = manifest_path.string();
  requireRegularFile(manifest_path, "missing: not a radarslam map directory");
  const YamlParams manifest = YamlParams::fromFile(mp);
  MapManifestSummary s;
  if (!manifest.has("format_version")) throw InputError(mp, "format_version missing");
  unsigned version = 0;
  manifest.get("format_version", version);
  if (version == 0 || version > kMapFormatVersion)
    throw InputError(mp, "map format version " + std::to_string(version) +
                             " is not one this radarslam reads (1.." + std::to_string(kMapFormatVersion) +
                             ")");
  s.format_version = version;
  std::string created = "0", keyframes = "0";
  manifest.get("created_ns", created);
  s.created_ns = static_cast<StampNs>(parseU64(created, mp, "created_ns"));
  manifest.section("counts").get("keyframes", keyframes);
  s.keyframes = parseU64(keyframes, mp, "counts.keyframes");
  if (version >= 2) s.layers = parseLayersManifest(manifest, mp);
  return s;
}

std::vector<MapFileEntry> listMapFiles(const fs::path& dir_in, bool with_layers) {
  const fs::path manifest_path = withoutTrailingSlash(dir_in) / "manifest.yaml";
  const std::string mp = manifest_path.string();
  const MapManifestSummary summary = readMapManifest(dir_in);  // version, layers section checked
  const YamlParams manifest = YamlParams::fromFile(mp);
  const YamlParams files = manifest.section("files");
  std::vector<MapFileEntry> out;
  for (const auto& entry : kFiles) {
    const YamlParams f = files.section(entry.key);
    std::string bytes_text;
    MapFileEntry e;
    f.get("name", e.name);
    f.get("sha256", e.sha256);
    f.get("bytes", bytes_text);
    if (e.name != entry.name || e.sha256.size() != 64 || bytes_text.empty())
      throw InputError(mp,
                       std::string("files.").append(entry.key).append(": name, bytes and sha256 required"));
    e.bytes = parseU64(bytes_text, mp, std::string("files.").append(entry.key).append(".bytes"));
    out.push_back(std::move(e));
  }
  if (with_layers && summary.layers)
    for (const auto& l : summary.layers->files) out.push_back({l.name, l.bytes, l.sha256});
  return out;
}

KeyframeMap loadMap(const fs::path& dir_in) {
  const fs::path dir = withoutTrailingSlash(dir_in);
  std::error_code ec;
  if (!hasManifest(dir)) {
    const fs::path backup = mapBackupDir(dir);
    if (!fs::exists(dir, ec) && hasManifest(backup)) {
      logger().logFmt(mrpt::system::LVL_WARN, "%s: restoring the map from %s (a save was interrupted)",
                      dir.string().c_str(), backup.string().c_str());
      fs::rename(backup, dir, ec);
      if (ec) throw InputError(backup.string(), "cannot restore map backup: " + ec.message());
    } else if (!fs::exists(dir, ec)) {
      throw InputError(dir.string(), "no map here (directory does not exist)");
    } else {
      requireRegularFile(dir / "manifest.yaml", "missing: not a radarslam map directory");
    }
  }

  const fs::path manifest_path = dir / "manifest.yaml";
  const std::string mp = manifest_path.string();
  requireRegularFile(manifest_path);
  const YamlParams manifest = YamlParams::fromFile(mp);
  if (!manifest.has("format_version")) throw InputError(mp, "format_version missing");
  unsigned version = 0;
  manifest.get("format_version", version);
  if (version > kMapFormatVersion)
    throw InputError(mp, "map format version " + std::to_string(version) +
                             " is newer than this radarslam reads (" + std::to_string(kMapFormatVersion) +
                             "); upgrade radarslam");
  if (version == 0) throw InputError(mp, "invalid format_version 0");

  KeyframeMap map;
  map.meta.format_version = version;
  std::string created = "0";
  manifest.get("created_ns", created);
  map.meta.created_ns = static_cast<StampNs>(parseU64(created, mp, "created_ns"));
  readString(manifest, mp, "software_version", map.meta.software_version);
  readString(manifest, mp, "source_dataset", map.meta.source_dataset);
  manifest.get("clouds_motion_compensated", map.meta.clouds_motion_compensated);
  const YamlParams sensor = manifest.section("sensor");
  sensor.get("num_azimuths", map.meta.sensor.num_azimuths);
  sensor.get("num_bins", map.meta.sensor.num_bins);
  sensor.get("range_resolution_m", map.meta.sensor.range_resolution_m);
  sensor.get("range_offset_m", map.meta.sensor.range_offset_m);
  mapcodec::validateSensor(map.meta.sensor, mp);

  const YamlParams files = manifest.section("files");
  for (const auto& entry : kFiles) {
    const YamlParams f = files.section(entry.key);
    std::string name, sha, bytes_text;
    f.get("name", name);
    f.get("sha256", sha);
    f.get("bytes", bytes_text);
    if (name != entry.name || sha.size() != 64 || bytes_text.empty())
      throw InputError(mp,
                       std::string("files.").append(entry.key).append(": name, bytes and sha256 required"));
    const fs::path path = dir / name;
    const std::string ps = path.string();
    const std::string bytes = readWholeFile(path);
    const auto expected_size =
        parseU64(bytes_text, mp, std::string("files.").append(entry.key).append(".bytes"));
    if (bytes.size() < expected_size)
      throw InputError(ps, "truncated: " + std::to_string(bytes.size()) + " bytes, manifest says " +
                               std::to_string(expected_size));
    if (bytes.size() > expected_size)
      throw InputError(ps, "size mismatch: " + std::to_string(bytes.size()) + " bytes, manifest says " +
                               std::to_string(expected_size));
    const std::string actual = sha256Hex(bytes);
    if (actual != sha)
      throw InputError(
          ps, "checksum mismatch (SHA-256 " + actual + ", manifest says " + sha + "): file is corrupt");
    const std::string key = entry.key;
    if (key == "parameters")
      map.meta.parameters_yaml = bytes;
    else if (key == "keyframes")
      decodeKeyframes(bytes, ps, map);
    else if (key == "points")
      decodePoints(bytes, ps, map);
    else
      decodeGraph(bytes, ps, map);
  }

  const YamlParams counts = manifest.section("counts");
  auto checkCount = [&](const char* key, std::size_t actual) {
    unsigned expected = 0;
    counts.get(key, expected);
    if (expected != actual)
      throw InputError(mp, std::string("counts.")
                               .append(key)
                               .append(" says ")
                               .append(std::to_string(expected))
                               .append(" but the file holds ")
                               .append(std::to_string(actual)));
  };
  checkCount("keyframes", map.keyframes.size());
  checkCount("points", map.points.size());
  checkCount("edges", map.edges.size());
  mapcodec::validateKeyframes(map, (dir / "keyframes.bin").string());
  mapcodec::validatePoints(map, (dir / "points.bin").string());
  mapcodec::validateGraph(map, (dir / "graph.bin").string());
  return map;
}

}  // namespace radarslam
