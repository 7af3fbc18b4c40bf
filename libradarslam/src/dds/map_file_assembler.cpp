#include "radarslam/dds/map_file_assembler.h"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/dds/map_file_publisher.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"

namespace radarslam::dds {

namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kMaxFiles = 64;         // a map has 5 (+4 layers)
constexpr std::uint32_t kMaxChunks = 1u << 20;  // 4 TiB at 4 MiB: far beyond any map
constexpr std::size_t kMaxPathBytes = 200;

std::string fileSha256(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  Sha256 sha;
  std::vector<char> buf(1 << 20);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0)
    sha.update(std::string_view(buf.data(), static_cast<std::size_t>(in.gcount())));
  return sha.hexDigest();
}

}  // namespace

std::string mapFilePathProblem(const std::string& path) {
  if (path.empty()) return "empty file path";
  if (path.size() > kMaxPathBytes) return "file path longer than " + std::to_string(kMaxPathBytes) + " bytes";
  if (path.front() == '/') return "absolute file path '" + path + "'";
  std::size_t components = 0;
  for (std::size_t start = 0; start <= path.size();) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    const std::string part = path.substr(start, end - start);
    if (part.empty() || part == "." || part == "..")
      return "file path '" + path + "' leaves or does not name a file of the map directory";
    for (char c : part)
      if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
            c == '_' || c == '-'))
        return "file path '" + path + "' has a character other than [A-Za-z0-9._-/]";
    ++components;
    start = end + 1;
  }
  if (components > 2) return "file path '" + path + "' is nested deeper than one directory";
  return {};
}

MapFileAssembler::MapFileAssembler(fs::path dir, std::string source, std::uint64_t max_bytes)
    : dir_(std::move(dir)), source_(std::move(source)), max_bytes_(max_bytes) {}

void MapFileAssembler::fail(const std::string& problem) const { throw InputError(source_, problem); }

std::size_t MapFileAssembler::filesComplete() const {
  std::size_t n = 0;
  for (const auto& [path, f] : files_) n += f.complete;
  return n;
}

void MapFileAssembler::reset(const MapFileChunkMsg& first) {
  // Only files this assembler created are removed (each path was checked before it was created).
  for (const auto& [path, f] : files_) {
    std::error_code ec;
    fs::remove(dir_ / path, ec);
  }
  files_.clear();
  manifest_.clear();
  manifest_read_ = false;
  complete_ = false;
  chunks_ = 0;
  bytes_ = 0;
  stated_bytes_ = 0;
  pub_ = first;
  pub_.data.clear();
  stamp_ = fromTimeMsg(first.header.stamp);
  started_ = true;
  if (pub_.file_count < 1 || pub_.file_count > kMaxFiles)
    fail("revision " + std::to_string(pub_.revision) + ": file count " + std::to_string(pub_.file_count) +
         " is not 1.." + std::to_string(kMaxFiles));
  if (pub_.total_chunks < pub_.file_count || pub_.total_chunks > kMaxChunks)
    fail("revision " + std::to_string(pub_.revision) + ": chunk count " + std::to_string(pub_.total_chunks) +
         " does not fit " + std::to_string(pub_.file_count) + " files");
  if (!isSha256Hex(pub_.manifest_sha256))
    fail("revision " + std::to_string(pub_.revision) + ": manifest SHA-256 is not 64 hex digits");
}

void MapFileAssembler::checkSamePublication(const MapFileChunkMsg& c) const {
  if (c.map_name != pub_.map_name || c.manifest_sha256 != pub_.manifest_sha256 ||
      c.file_count != pub_.file_count || c.total_chunks != pub_.total_chunks)
    fail("revision " + std::to_string(c.revision) + ": chunk of '" + c.path +
         "' disagrees with the publication (map name, manifest SHA-256, file or chunk count)");
}

bool MapFileAssembler::add(const MapFileChunkMsg& c) {
  const StampNs stamp = fromTimeMsg(c.header.stamp);
  if (started_) {
    const bool older = c.revision < pub_.revision || (c.revision == pub_.revision && stamp < stamp_);
    const bool newer = c.revision > pub_.revision || (c.revision == pub_.revision && stamp > stamp_);
    if (older || (complete_ && !newer)) {
      ++ignored_;
      return complete_;
    }
    if (newer) reset(c);
  } else {
    reset(c);
  }
  checkSamePublication(c);
  if (const std::string p = mapFilePathProblem(c.path); !p.empty()) fail(p);
  const std::string& path = c.path;
  if (c.file_index >= pub_.file_count)
    fail(path + ": file index " + std::to_string(c.file_index) + " >= file count " +
         std::to_string(pub_.file_count));
  if ((path == "manifest.yaml") != (c.file_index == 0))
    fail(path + ": file 0 must be manifest.yaml and only file 0");
  if (!isSha256Hex(c.file_sha256)) fail(path + ": file SHA-256 is not 64 hex digits");
  if (c.chunk_count < 1 || c.chunk_index >= c.chunk_count)
    fail(path + ": chunk " + std::to_string(c.chunk_index) + " of " + std::to_string(c.chunk_count));
  if (c.file_size > static_cast<std::uint64_t>(c.chunk_count) * kMaxMapFileChunkBytes)
    fail(path + ": " + std::to_string(c.file_size) + " bytes cannot be " + std::to_string(c.chunk_count) +
         " chunks of at most " + std::to_string(kMaxMapFileChunkBytes) + " bytes");
  if (c.data.size() > kMaxMapFileChunkBytes)
    fail(path + ": chunk of " + std::to_string(c.data.size()) + " bytes (at most " +
         std::to_string(kMaxMapFileChunkBytes) + ")");
  if (c.offset > c.file_size || c.data.size() > c.file_size - c.offset)
    fail(path + ": chunk " + std::to_string(c.chunk_index) + " (bytes " + std::to_string(c.offset) + "+" +
         std::to_string(c.data.size()) + ") beyond the file size " + std::to_string(c.file_size));

  auto it = files_.find(path);
  if (it == files_.end()) {
    for (const auto& [other, f] : files_)
      if (f.index == c.file_index)
        fail(path + ": file index " + std::to_string(c.file_index) + " also used by " + other);
    if (files_.size() >= pub_.file_count)
      fail(path + ": more files than the publication's " + std::to_string(pub_.file_count));
    if (c.file_size > max_bytes_ - stated_bytes_)
      fail(path + ": the map's files exceed the limit of " + std::to_string(max_bytes_ >> 20) +
           " MiB (--map-max-mb)");
    stated_bytes_ += c.file_size;
    FileState f;
    f.index = c.file_index;
    f.size = c.file_size;
    f.sha256 = c.file_sha256;
    f.chunk_count = c.chunk_count;
    if (manifest_read_ && path != "manifest.yaml") checkAgainstManifest(path, f);
    if (path.find('/') != std::string::npos) {
      std::error_code ec;
      fs::create_directory(dir_ / fs::path(path).parent_path(), ec);  // the one subdirectory allowed
    }
    it = files_.emplace(path, std::move(f)).first;
  }
  FileState& f = it->second;
  if (f.index != c.file_index || f.size != c.file_size || f.sha256 != c.file_sha256)
    fail(path + ": chunk " + std::to_string(c.chunk_index) +
         " disagrees with the file's other chunks (index, size or SHA-256)");
  if (f.chunk_count != c.chunk_count)
    fail(path + ": chunk count mismatch (" + std::to_string(c.chunk_count) + ", earlier chunks said " +
         std::to_string(f.chunk_count) + ")");
  if (f.complete || f.chunks.count(c.chunk_index))
    fail(path + ": duplicate chunk " + std::to_string(c.chunk_index) + " of " +
         std::to_string(c.chunk_count));
  if (chunks_ + 1 > pub_.total_chunks)
    fail(path + ": more chunks than the publication's " + std::to_string(pub_.total_chunks));

  const fs::path file = dir_ / path;
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) fail(path + ": cannot write " + file.string());
  std::size_t written = 0;
  while (written < c.data.size()) {
    const ssize_t n = ::pwrite(fd, c.data.data() + written, c.data.size() - written,
                               static_cast<off_t>(c.offset + written));
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (written != c.data.size()) fail(path + ": cannot write " + file.string() + " (disk full?)");
  f.chunks.emplace(c.chunk_index, std::make_pair(c.offset, static_cast<std::uint64_t>(c.data.size())));
  ++chunks_;
  bytes_ += c.data.size();
  if (f.chunks.size() == f.chunk_count) finishFile(path, f);

  if (filesComplete() == pub_.file_count) {
    if (chunks_ != pub_.total_chunks)
      fail("revision " + std::to_string(pub_.revision) + ": " + std::to_string(chunks_) +
           " chunks make all files, the publication says " + std::to_string(pub_.total_chunks));
    if (!manifest_read_) fail("revision " + std::to_string(pub_.revision) + ": no manifest.yaml");
    for (const auto& e : listMapFiles(dir_, false))  // what loadMap reads must all be there
      if (!files_.count(e.name)) fail(e.name + ": listed by the manifest but not in the publication");
    complete_ = true;
  }
  return complete_;
}

void MapFileAssembler::finishFile(const std::string& path, FileState& f) {
  // The chunks must tile the file: 0, then each one where the previous ended, up to the size.
  std::uint64_t expect = 0;
  for (const auto& [index, range] : f.chunks) {
    if (range.first != expect || (range.second == 0 && f.size != 0))
      fail(path + ": chunk " + std::to_string(index) + " at byte " + std::to_string(range.first) +
           ", expected byte " + std::to_string(expect) + " (chunks overlap or leave a gap)");
    expect += range.second;
  }
  if (expect != f.size)
    fail(path + ": chunks hold " + std::to_string(expect) + " bytes, the file has " + std::to_string(f.size));
  const fs::path file = dir_ / path;
  std::error_code ec;
  if (fs::file_size(file, ec) != f.size || ec) fail(path + ": written file has the wrong size");
  const std::string actual = fileSha256(file);
  if (actual != f.sha256)
    fail(path + ": SHA-256 mismatch (received " + actual + ", chunks say " + f.sha256 + ")");
  f.complete = true;
  if (path != "manifest.yaml") return;
  if (actual != pub_.manifest_sha256)
    fail("manifest.yaml: SHA-256 " + actual + " is not the publication's " + pub_.manifest_sha256);
  try {
    for (const auto& e : listMapFiles(dir_, true)) manifest_[e.name] = {e.bytes, e.sha256};
  } catch (const InputError& e) {
    fail("manifest.yaml: " + e.problem());
  }
  manifest_read_ = true;
  if (pub_.file_count > manifest_.size() + 1)
    fail("revision " + std::to_string(pub_.revision) + ": " + std::to_string(pub_.file_count) +
         " files, the manifest lists " + std::to_string(manifest_.size()));
  for (const auto& [other, state] : files_)
    if (other != "manifest.yaml") checkAgainstManifest(other, state);
}

void MapFileAssembler::checkAgainstManifest(const std::string& path, const FileState& f) const {
  const auto it = manifest_.find(path);
  if (it == manifest_.end()) fail(path + ": not a file the manifest lists");
  if (it->second.first != f.size || it->second.second != f.sha256)
    fail(path + ": size or SHA-256 differs from the manifest's");
}

}  // namespace radarslam::dds
