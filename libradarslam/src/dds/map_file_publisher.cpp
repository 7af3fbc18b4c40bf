#include "radarslam/dds/map_file_publisher.h"

#include <sys/stat.h>

#include <fstream>
#include <vector>

#include "radarslam/core/errors.h"
#include "radarslam/dds/domain.h"
#include "radarslam/map/map_io.h"
#include "radarslam/map/sha256.h"

namespace radarslam::dds {

namespace fs = std::filesystem;

namespace {

std::uint32_t chunksOf(std::uint64_t bytes, std::size_t chunk) {
  return bytes == 0 ? 1u : static_cast<std::uint32_t>((bytes + chunk - 1) / chunk);
}

// Opens a regular file (never a FIFO or a directory) of the expected size.
std::ifstream openChecked(const fs::path& path, std::uint64_t bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw InputError(path.string(), "missing or not a regular file");
  if (static_cast<std::uint64_t>(st.st_size) != bytes)
    throw InputError(path.string(), "size mismatch: " + std::to_string(st.st_size) +
                                        " bytes, manifest says " + std::to_string(bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot be read");
  return in;
}

// Reads `in` in blocks of `chunk` bytes, hashing everything; calls fn(block) for each block.
template <class Fn>
std::string streamFile(std::ifstream& in, const fs::path& path, std::uint64_t bytes, std::size_t chunk,
                       Fn fn) {
  Sha256 sha;
  std::vector<std::uint8_t> buf;
  std::uint64_t done = 0;
  do {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk, bytes - done));
    buf.resize(n);
    if (n > 0 && !in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(n)))
      throw InputError(path.string(), "truncated while reading (" + std::to_string(done) + " of " +
                                          std::to_string(bytes) + " bytes)");
    sha.update(std::span<const unsigned char>(buf.data(), n));
    fn(buf, done);
    done += n;
  } while (done < bytes);
  return sha.hexDigest();
}

}  // namespace

MapFilesPublisher::MapFilesPublisher(Domain& domain, MapFilesParams params)
    : domain_(domain), params_(params) {
  if (params_.chunk_bytes < 1 || params_.chunk_bytes > kMaxMapFileChunkBytes)
    throw InputError("map files",
                     "chunk size must be 1.." + std::to_string(kMaxMapFileChunkBytes) + " bytes");
}

MapFilesPublisher::~MapFilesPublisher() = default;

std::uint32_t MapFilesPublisher::matchedSubscriptions() const {
  return writer_ ? writer_->matchedSubscriptions() : 0;
}

MapFilesSummary forEachMapFileChunk(const fs::path& map_dir, const MapFilesPublication& pub,
                                    const MapFilesParams& params,
                                    const std::function<void(const MapFilesSummary&)>& start,
                                    const std::function<void(const MapFileChunkMsg&)>& fn) {
  if (params.chunk_bytes < 1 || params.chunk_bytes > kMaxMapFileChunkBytes)
    throw InputError("map files",
                     "chunk size must be 1.." + std::to_string(kMaxMapFileChunkBytes) + " bytes");
  // The manifest (small) is held in memory: what is sent is exactly what was checked.
  const fs::path manifest_path = map_dir / "manifest.yaml";
  std::string manifest;
  {
    struct stat st {};
    if (::stat(manifest_path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
      throw InputError(manifest_path.string(), "missing or not a regular file");
    std::ifstream in = openChecked(manifest_path, static_cast<std::uint64_t>(st.st_size));
    manifest.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string manifest_sha = sha256Hex(manifest);
  if (!pub.manifest_sha256.empty() && manifest_sha != pub.manifest_sha256)
    throw InputError(manifest_path.string(), "changed while the map was being read");
  const std::vector<MapFileEntry> files = listMapFiles(map_dir, params.with_layers);

  // Check every file before anything is sent: a bad map leaves the previous publication alone.
  for (const auto& f : files) {
    const fs::path path = map_dir / f.name;
    std::ifstream in = openChecked(path, f.bytes);
    const std::string actual = streamFile(in, path, f.bytes, params.chunk_bytes, [](auto&, auto) {});
    if (actual != f.sha256)
      throw InputError(path.string(), "checksum mismatch (SHA-256 " + actual + ", manifest says " + f.sha256 +
                                          "): the map files are not published");
  }

  MapFilesSummary summary;
  summary.files = files.size() + 1;
  summary.chunks = chunksOf(manifest.size(), params.chunk_bytes);
  for (const auto& f : files) summary.chunks += chunksOf(f.bytes, params.chunk_bytes);
  const MapFilesSummary totals = summary;
  summary.bytes = 0;  // counted while sending
  if (start) start(totals);
  MapFileChunkMsg msg;
  msg.header = {toTimeMsg(pub.stamp), "map"};
  msg.map_name = pub.map_name;
  msg.revision = pub.revision;
  msg.manifest_sha256 = manifest_sha;
  msg.file_count = static_cast<std::uint32_t>(summary.files);
  msg.total_chunks = static_cast<std::uint32_t>(summary.chunks);
  auto describe = [&](std::uint32_t index, const std::string& path, std::uint64_t bytes,
                      const std::string& sha) {
    msg.file_index = index;
    msg.path = path;
    msg.file_size = bytes;
    msg.file_sha256 = sha;
    msg.chunk_count = chunksOf(bytes, params.chunk_bytes);
    msg.chunk_index = 0;
  };
  auto send = [&](const std::vector<std::uint8_t>& data, std::uint64_t offset) {
    msg.offset = offset;
    msg.data = data;
    fn(msg);
    ++msg.chunk_index;
    summary.bytes += data.size();
  };

  describe(0, "manifest.yaml", manifest.size(), manifest_sha);
  for (std::uint64_t off = 0;;) {
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::uint64_t>(params.chunk_bytes, manifest.size() - off));
    send(std::vector<std::uint8_t>(manifest.begin() + static_cast<std::ptrdiff_t>(off),
                                   manifest.begin() + static_cast<std::ptrdiff_t>(off + n)),
         off);
    off += n;
    if (off >= manifest.size()) break;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto& f = files[i];
    const fs::path path = map_dir / f.name;
    describe(static_cast<std::uint32_t>(i + 1), f.name, f.bytes, f.sha256);
    std::ifstream in = openChecked(path, f.bytes);
    const std::string sent = streamFile(in, path, f.bytes, params.chunk_bytes, send);
    if (sent != f.sha256) throw InputError(path.string(), "changed while it was being published");
  }
  return summary;
}

MapFilesSummary MapFilesPublisher::publish(const fs::path& map_dir, const MapFilesPublication& pub) {
  bool replaced = false;
  try {
    return forEachMapFileChunk(
        map_dir, pub, params_,
        [&](const MapFilesSummary& totals) {
          // One writer per publication, deep enough for all of its chunks (Cyclone 0.10 keeps for
          // late joiners what the durability service's history says; TopicQos::latchedLast sets
          // it): a late joiner gets every chunk, and the previous publication's chunks go with
          // the previous writer.
          writer_.reset();
          replaced = true;
          writer_ = std::make_unique<Publisher<MapFileChunkMsg>>(
              domain_, kMapFilesTopic, TopicQos::latchedLast(static_cast<std::int32_t>(totals.chunks)));
        },
        [&](const MapFileChunkMsg& chunk) { writer_->publish(chunk); });
  } catch (...) {
    // A file that failed its check threw before the writer was replaced: the previous publication
    // stays. One that changed while it was sent withdraws this one (receivers would reject it).
    if (replaced) writer_.reset();
    throw;
  }
}

}  // namespace radarslam::dds
