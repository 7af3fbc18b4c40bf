// Layer file formats: encoders and checked readers (map/layer_files.h).
#include "radarslam/map/layer_files.h"

#include <sys/stat.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "radarslam/map/octomap_slab.h"
#include "radarslam/map/sha256.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {

constexpr unsigned char kUnknownPixel = 205;

unsigned char cellPixel(int v) {
  return v < 0 || v > 100 ? kUnknownPixel
                          : static_cast<unsigned char>(std::lround(255.0 * (100 - v) / 100.0));
}

// Inverse of cellPixel for the 102 pixel values it produces; -2 for any other value.
struct PixelTable {
  std::int8_t cell[256];
  PixelTable() {
    std::memset(cell, -2, sizeof cell);
    cell[kUnknownPixel] = -1;
    for (int v = 0; v <= 100; ++v) cell[cellPixel(v)] = static_cast<std::int8_t>(v);
  }
};

std::vector<std::string> splitWords(const std::string& line) {
  std::istringstream ss(line);
  std::vector<std::string> words;
  for (std::string w; ss >> w;) words.push_back(w);
  return words;
}

// "KEY a b c" -> {a, b, c}, or InputError.
std::vector<std::string> pcdLine(const std::vector<std::string>& lines, std::size_t i, const char* key,
                                 const std::string& file) {
  auto words = i < lines.size() ? splitWords(lines[i]) : std::vector<std::string>{};
  if (words.empty() || words[0] != key)
    throw InputError(file, std::string("PCD header: expected ") + key + " in line " + std::to_string(i + 1));
  words.erase(words.begin());
  return words;
}

}  // namespace

unsigned char gridPixel(int cell) { return cellPixel(cell); }

int gridCellOfPixel(unsigned char pixel) {
  static const PixelTable table;
  return table.cell[pixel];
}

std::string gridPgm(const std::vector<std::int8_t>& cells, std::uint32_t width, std::uint32_t height) {
  std::string out = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  const std::size_t header = out.size();
  out.resize(header + static_cast<std::size_t>(width) * height);
  for (std::uint32_t row = 0; row < height; ++row) {
    const std::int8_t* src = cells.data() + static_cast<std::size_t>(height - 1 - row) * width;
    char* dst = out.data() + header + static_cast<std::size_t>(row) * width;
    for (std::uint32_t col = 0; col < width; ++col) dst[col] = static_cast<char>(cellPixel(src[col]));
  }
  return out;
}

std::string gridRosYaml(const std::string& image, float resolution, double origin_x, double origin_y) {
  char res[32];
  const auto [end, ec] = std::to_chars(res, res + sizeof res - 1, resolution);  // shortest round trip
  *end = '\0';
  (void)ec;
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "image: %s\nmode: scale\nresolution: %s\norigin: [%.17g, %.17g, 0]\nnegate: 0\n"
                "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
                image.c_str(), res, origin_x, origin_y);
  return yaml;
}

std::string cloudPcdHeader(std::uint64_t points) {
  const std::string count = std::to_string(points);
  std::string pcd = "# .PCD v0.7 - radarslam map points, map frame\nVERSION 0.7\nFIELDS x y z intensity\n";
  pcd.append("SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH ").append(count);
  pcd.append("\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS ").append(count).append("\nDATA binary\n");
  return pcd;
}

std::vector<std::uint8_t> cloudPayload(const KeyframeMap& map) {
  std::uint64_t n = 0;
  for (const auto& kf : map.keyframes) n += kf.points.size();
  std::vector<std::uint8_t> data(n * kCloudRecordBytes);
  std::size_t at = 0;
  for (const auto& kf : map.keyframes) {
    const double c = std::cos(kf.pose.phi), s = std::sin(kf.pose.phi);
    for (const auto& p : kf.points) {
      float v[4];
      cloudRecord(kf, c, s, p, v);
      std::memcpy(data.data() + at, v, sizeof v);  // little-endian host
      at += sizeof v;
    }
  }
  return data;
}

std::string cloudPcd(const KeyframeMap& map, std::uint64_t* points) {
  const std::vector<std::uint8_t> data = cloudPayload(map);
  const std::uint64_t n = data.size() / kCloudRecordBytes;
  if (points) *points = n;
  std::string pcd = cloudPcdHeader(n);
  pcd.append(data.begin(), data.end());
  return pcd;
}

template <class Byte>
std::string readLayerFile(const fs::path& map_dir, const LayerFileEntry& entry,
                          const std::string& last_header_line, std::vector<Byte>& body) {
  static_assert(sizeof(Byte) == 1);
  const fs::path path = map_dir / entry.name;
  const std::string ps = path.string();
  requireRegularFile(path, "missing layer file (listed in manifest.yaml)");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(ps, "cannot stat the layer file");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size != entry.bytes)
    throw InputError(ps, "size mismatch: " + std::to_string(size) + " bytes, manifest says " +
                             std::to_string(entry.bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(ps, "cannot open the layer file");
  std::string header, line;
  bool found = false;
  for (int i = 0; i < 64 && header.size() < 4096 && std::getline(in, line); ++i) {
    header.append(line).push_back('\n');
    if (line == last_header_line) {
      found = true;
      break;
    }
  }
  if (!found || header.size() > size)
    throw InputError(ps, "malformed header: no '" + last_header_line + "' line within 64 lines");
  body.resize(size - header.size());
  in.read(reinterpret_cast<char*>(body.data()), static_cast<std::streamsize>(body.size()));
  if (!in) throw InputError(ps, "read failed");
  Sha256 sha;
  sha.update(header);
  sha.update({reinterpret_cast<const unsigned char*>(body.data()), body.size()});
  const std::string actual = sha.hexDigest();
  if (actual != entry.sha256)
    throw InputError(ps, "checksum mismatch (SHA-256 " + actual + ", manifest says " + entry.sha256 +
                             "): layer file is corrupt");
  return header;
}
template std::string readLayerFile(const fs::path&, const LayerFileEntry&, const std::string&,
                                   std::vector<std::int8_t>&);
template std::string readLayerFile(const fs::path&, const LayerFileEntry&, const std::string&,
                                   std::vector<std::uint8_t>&);

namespace {

// Cells of a P5 grid layer file of width x height (pixels flipped back to cells, row 0 = lowest y).
std::vector<std::int8_t> readPgmCells(const fs::path& map_dir, const LayerFileEntry& e, std::uint32_t width,
                                      std::uint32_t height) {
  const std::string file = (map_dir / e.name).string();
  std::vector<std::int8_t> px;
  const std::string header = readLayerFile(map_dir, e, "255", px);
  const std::string expected = "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
  if (header != expected || px.size() != static_cast<std::size_t>(width) * height)
    throw InputError(file, "not the " + std::to_string(width) + "x" + std::to_string(height) +
                               " 8-bit P5 image the manifest describes");
  // Back to cells, flipping rows in place (image top row = highest y; cells row 0 = lowest y).
  static const PixelTable table;
  const std::size_t w = width, h = height;
  std::vector<std::int8_t> tmp(w);
  for (std::size_t row = 0; row < h / 2; ++row) {
    std::int8_t* a = px.data() + row * w;
    std::int8_t* b = px.data() + (h - 1 - row) * w;
    std::memcpy(tmp.data(), a, w);
    std::memcpy(a, b, w);
    std::memcpy(b, tmp.data(), w);
  }
  for (auto& v : px) {
    const std::int8_t c = table.cell[static_cast<unsigned char>(v)];
    if (c == -2)
      throw InputError(file, "pixel value " + std::to_string(static_cast<unsigned char>(v)) +
                                 " is not one a radarslam grid layer holds");
    v = c;
  }
  return px;
}

}  // namespace

std::vector<std::int8_t> readGridLayer(const fs::path& map_dir, const MapLayersManifest& layers) {
  return readPgmCells(map_dir, layers.file("grid"), layers.grid_width, layers.grid_height);
}

std::vector<std::int8_t> readGridOverviewLayer(const fs::path& map_dir, const MapLayersManifest& layers) {
  return readPgmCells(map_dir, layers.file("grid_overview"), layers.tiling.overview_width,
                      layers.tiling.overview_height);
}

namespace {
// Opens a layer file read tile by tile (never whole): it must be a regular file of exactly
// header + body_bytes bytes (= the manifest's size) starting with `header`. Returns the stream
// positioned after the header; `what` describes the expected content in errors.
std::ifstream openLayerBody(const fs::path& path, const LayerFileEntry& e, const std::string& header,
                            std::uint64_t body_bytes, const std::string& what) {
  const std::string file = path.string();
  requireRegularFile(path, "missing layer file (listed in manifest.yaml)");
  const std::uint64_t size = header.size() + body_bytes;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || static_cast<std::uint64_t>(st.st_size) != size || size != e.bytes)
    throw InputError(file, "size mismatch: " + std::to_string(st.st_size) + " bytes, manifest says " +
                               std::to_string(e.bytes) + " (" + what + ")");
  std::ifstream in(path, std::ios::binary);
  std::string got(header.size(), '\0');
  if (!in || !in.read(got.data(), static_cast<std::streamsize>(got.size())) || got != header)
    throw InputError(file, "header is not the one radarslam writes for " + what);
  return in;
}

// A tile index file (checked against the manifest): its text after the first line, which must be
// `first_line`; `file` receives its path for error messages.
std::string readTileIndexText(const fs::path& map_dir, const LayerFileEntry& e, const char* first_line,
                              std::string& file) {
  std::vector<std::uint8_t> body;
  const std::string header = readLayerFile(map_dir, e, first_line, body);
  file = (map_dir / e.name).string();
  if (header != std::string(first_line) + "\n")
    throw InputError(file, std::string("expected the first line '") + first_line + "'");
  return std::string(body.begin(), body.end());
}
}  // namespace

std::vector<GridTileEntry> readGridTileIndexLayer(const fs::path& map_dir, const MapLayersManifest& layers) {
  std::string file;
  const std::string text = readTileIndexText(map_dir, layers.file("grid_tiles"), kGridTilesHeader, file);
  return parseGridTileIndex(text, layers.tiling, file);
}

void forEachGridTileLayer(
    const fs::path& map_dir, const MapLayersManifest& layers, const std::vector<GridTileEntry>& index,
    const std::function<void(const GridTileEntry&, const std::vector<std::int8_t>&)>& fn) {
  const LayerFileEntry& e = layers.file("grid");
  const fs::path path = map_dir / e.name;
  const std::string file = path.string();
  const GridTiling& t = layers.tiling;
  const std::string header = "P5\n" + std::to_string(t.width) + " " + std::to_string(t.height) + "\n255\n";
  const std::string what = "a " + std::to_string(t.width) + "x" + std::to_string(t.height) + " P5 image";
  std::ifstream in = openLayerBody(path, e, header, std::uint64_t{t.width} * t.height, what);
  static const PixelTable table;
  std::vector<std::int8_t> band, tile;
  std::uint32_t band_ty = UINT32_MAX;
  for (const GridTileEntry& entry : index) {
    const TileRect r = tileRect(t, entry.tx, entry.ty);
    if (entry.ty != band_ty) {  // read the image rows of this row of tiles (cells rows row0..row0+rows)
      band_ty = entry.ty;
      band.resize(std::size_t{r.rows} * t.width);
      const std::uint64_t first_image_row = t.height - (r.row0 + r.rows);
      in.seekg(static_cast<std::streamoff>(header.size() + first_image_row * t.width));
      if (!in.read(reinterpret_cast<char*>(band.data()), static_cast<std::streamsize>(band.size())))
        throw InputError(file, "read failed at tile row " + std::to_string(entry.ty));
    }
    tile.resize(std::size_t{r.cols} * r.rows);
    for (std::uint32_t row = 0; row < r.rows; ++row) {  // band row 0 = the tile's highest cell row
      const std::int8_t* src = band.data() + std::size_t{r.rows - 1 - row} * t.width + r.col0;
      std::int8_t* dst = tile.data() + std::size_t{row} * r.cols;
      for (std::uint32_t col = 0; col < r.cols; ++col) {
        const std::int8_t c = table.cell[static_cast<unsigned char>(src[col])];
        if (c == -2)
          throw InputError(file, "pixel value " + std::to_string(static_cast<unsigned char>(src[col])) +
                                     " is not one a radarslam grid layer holds");
        dst[col] = c;
      }
    }
    const std::string sha = sha256Hex({reinterpret_cast<const unsigned char*>(tile.data()), tile.size()});
    if (sha != entry.sha256)
      throw InputError(file, "checksum mismatch in tile (" + std::to_string(entry.tx) + ", " +
                                 std::to_string(entry.ty) + "): SHA-256 " + sha + ", " + kGridTilesLayerFile +
                                 " says " + entry.sha256 + ": layer file is corrupt");
    fn(entry, tile);
  }
}

std::vector<std::uint8_t> readCloudLayer(const fs::path& map_dir, const MapLayersManifest& layers,
                                         std::uint64_t& points) {
  const LayerFileEntry& e = layers.file("cloud");
  const std::string file = (map_dir / e.name).string();
  std::vector<std::uint8_t> data;
  const std::string header = readLayerFile(map_dir, e, "DATA binary", data);
  std::vector<std::string> lines;
  {
    std::istringstream ss(header);
    for (std::string l; std::getline(ss, l);)
      if (!l.empty() && l[0] != '#') lines.push_back(l);
  }
  using V = std::vector<std::string>;
  if (pcdLine(lines, 1, "FIELDS", file) != V{"x", "y", "z", "intensity"} ||
      pcdLine(lines, 2, "SIZE", file) != V{"4", "4", "4", "4"} ||
      pcdLine(lines, 3, "TYPE", file) != V{"F", "F", "F", "F"} ||
      pcdLine(lines, 4, "COUNT", file) != V{"1", "1", "1", "1"} ||
      pcdLine(lines, 6, "HEIGHT", file) != V{"1"})
    throw InputError(file, "PCD header: expected fields x y z intensity, FLOAT32, height 1");
  const std::string n = std::to_string(layers.cloud_points);
  if (pcdLine(lines, 5, "WIDTH", file) != V{n} || pcdLine(lines, 8, "POINTS", file) != V{n} ||
      data.size() != layers.cloud_points * kCloudRecordBytes)
    throw InputError(
        file, "PCD holds " + std::to_string(data.size() / kCloudRecordBytes) + " points, manifest says " + n);
  points = layers.cloud_points;
  return data;
}

std::vector<CloudTileEntry> readCloudTileIndexLayer(const fs::path& map_dir,
                                                    const MapLayersManifest& layers) {
  std::string file;
  const std::string text = readTileIndexText(map_dir, layers.file("cloud_tiles"), kCloudTilesHeader, file);
  return parseCloudTileIndex(text, layers.tiling, layers.cloud_points, file);
}

void forEachCloudTileLayer(
    const fs::path& map_dir, const MapLayersManifest& layers, const std::vector<CloudTileEntry>& index,
    const std::function<void(const CloudTileEntry&, const std::vector<std::uint8_t>&)>& fn) {
  const LayerFileEntry& e = layers.file("cloud");
  const fs::path path = map_dir / e.name;
  const std::string file = path.string();
  const std::string header = cloudPcdHeader(layers.cloud_points);
  std::ifstream in =
      openLayerBody(path, e, header, layers.cloud_points * kCloudRecordBytes,
                    "a PCD of the manifest's " + std::to_string(layers.cloud_points) + " points");
  std::vector<std::uint8_t> data;
  for (const CloudTileEntry& t : index) {
    data.resize(t.count * kCloudRecordBytes);
    in.seekg(static_cast<std::streamoff>(header.size() + t.first * kCloudRecordBytes));
    if (!in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size())))
      throw InputError(file,
                       "read failed at tile (" + std::to_string(t.tx) + ", " + std::to_string(t.ty) + ")");
    const std::string sha = sha256Hex({data.data(), data.size()});
    if (sha != t.sha256)
      throw InputError(file, "checksum mismatch in tile (" + std::to_string(t.tx) + ", " +
                                 std::to_string(t.ty) + "): SHA-256 " + sha + ", " + kCloudTilesLayerFile +
                                 " says " + t.sha256 + ": layer file is corrupt");
    fn(t, data);
  }
}

std::vector<std::int8_t> readOctomapLayer(const fs::path& map_dir, const MapLayersManifest& layers) {
  const LayerFileEntry& e = layers.file("octomap");
  const std::string file = (map_dir / e.name).string();
  std::vector<std::int8_t> data;
  const std::string header = readLayerFile(map_dir, e, "data", data);
  std::istringstream ss(header);
  std::string line;
  std::getline(ss, line);
  if (line.rfind("# Octomap OcTree binary file", 0) != 0)
    throw InputError(file, "not an OctoMap binary file (first line '" + line.substr(0, 64) + "')");
  bool id_ok = false, res_ok = false;
  std::string size_text;
  while (std::getline(ss, line)) {
    const auto w = splitWords(line);
    if (w.size() == 2 && w[0] == "id") id_ok = w[1] == "OcTree";
    if (w.size() == 2 && w[0] == "size") size_text = w[1];
    if (w.size() == 2 && w[0] == "res") {
      const double r = std::atof(w[1].c_str());
      res_ok = r > 0 && std::abs(r - layers.params.octomap.resolution_m) <= 1e-5 * r;
    }
  }
  if (!id_ok || !res_ok)
    throw InputError(file, "OctoMap header: expected id OcTree and the resolution the manifest gives");
  const auto nodes = octreeBinaryNodeCount({reinterpret_cast<const char*>(data.data()), data.size()});
  if (!nodes || std::to_string(*nodes) != size_text)
    throw InputError(
        file, "OctoMap data is malformed or does not hold the " + size_text + " nodes its header says");
  return data;
}

}  // namespace radarslam
