// Building the published layers of a map and their manifest section (map/map_layers.h).
#include "radarslam/map/map_layers.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "manifest_strings.h"
#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/map/layer_files.h"
#include "radarslam/map/octomap_slab.h"
#include "radarslam/map/sha256.h"

namespace radarslam {
namespace fs = std::filesystem;

namespace {

const char* fillName(OctomapExportParams::Fill f) {
  return f == OctomapExportParams::Fill::grid_columns ? "grid_columns" : "point_rays";
}

OctomapExportParams::Fill parseFill(const YamlParams& yaml, const std::string& name) {
  if (name == "grid_columns") return OctomapExportParams::Fill::grid_columns;
  if (name != "point_rays") yaml.fail("octomap_fill", "'" + name + "' is not grid_columns or point_rays");
  return OctomapExportParams::Fill::point_rays;
}

// Writes the parts one after another into `path` and flushes it to disk.
void writeSynced(const fs::path& path, std::initializer_list<std::string_view> parts) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  for (const std::string_view bytes : parts)
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw InputError(path.string(), "write failed (disk full or no permission?)");
  fsyncFile(path);
}

std::optional<std::uint64_t> parseCount(const std::string& text) {
  if (text.empty() || text.size() > 19 || text.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stoull(text);
}

LayerFileEntry entry(const std::string& key, const std::string& name, std::string_view bytes) {
  return {key, name, bytes.size(), sha256Hex(bytes)};
}

}  // namespace

void loadParams(const YamlParams& yaml, MapLayerParams& p) {
  yaml.get("grid_resolution_m", p.grid.resolution_m, Range::above(0, 100));
  yaml.get("grid_margin_m", p.grid.margin_m, Range::closed(0, 1000));
  yaml.get("grid_log_odds_hit", p.grid.log_odds_hit, Range::closed(0, 100));
  yaml.get("grid_log_odds_miss", p.grid.log_odds_miss, Range::closed(-100, 0));
  yaml.get("grid_log_odds_clamp", p.grid.log_odds_clamp, Range::above(0, 100));
  std::string fill = fillName(p.octomap.fill);
  yaml.get("octomap_fill", fill);
  p.octomap.fill = parseFill(yaml, fill);
  yaml.get("octomap_resolution_m", p.octomap.resolution_m, Range::above(0, 100));
  yaml.get("octomap_max_range_m", p.octomap.max_range_m, Range::closed(-1, 1e6));
  yaml.get("grid_tile_cells", p.tiling.tile_cells, Range::closed(16, 8192));
  yaml.get("grid_tile_above_cells", p.tiling.tile_above_cells, Range::closed(1, 1e12));
  yaml.get("grid_overview_max_cells", p.tiling.overview_max_cells, Range::closed(1, 1e9));
}

const LayerFileEntry& MapLayersManifest::file(const std::string& key) const {
  for (const auto& f : files)
    if (f.key == key) return f;
  throw InputError("manifest.yaml", "layers.files." + key + " missing");
}

std::vector<std::int8_t> occupancyCells(const OccupancyRaster& r) {
  std::vector<std::int8_t> cells(r.p_occupied.size());
  for (std::size_t i = 0; i < r.p_occupied.size(); ++i) {
    const bool seen = r.observed.empty() ? r.p_occupied[i] != 0.5f : r.observed[i] != 0;
    cells[i] = seen ? static_cast<std::int8_t>(std::lround(100.0 * r.p_occupied[i])) : std::int8_t{-1};
  }
  return cells;
}

MapLayersManifest writeMapLayers(const KeyframeMap& map, const fs::path& map_dir,
                                 const MapLayerParams& params) {
  const fs::path dir = map_dir / kLayersDir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), "cannot create the layers directory: " + ec.message());
  MapLayersManifest m;
  m.params = params;
  const std::string prefix = std::string(kLayersDir) + "/";

  // Grid first; its raster also makes the OctoMap when the fill and resolution allow. A large
  // grid is tiled for publishing, so it may exceed what one image should hold.
  GridExportParams grid_params = params.grid;
  grid_params.max_cells = std::max(grid_params.max_cells, kMaxLayerGridCells);
  std::optional<OccupancyRaster> raster = buildOccupancy(map, grid_params);
  m.grid_width = static_cast<std::uint32_t>(raster->width);
  m.grid_height = static_cast<std::uint32_t>(raster->height);
  m.grid_origin_x = raster->x_min;
  m.grid_origin_y = raster->y_min;
  {
    const std::vector<std::int8_t> cells = occupancyCells(*raster);
    m.grid_cells_sha256 = sha256Hex({reinterpret_cast<const unsigned char*>(cells.data()), cells.size()});
    const std::string pgm = gridPgm(cells, m.grid_width, m.grid_height);
    writeSynced(dir / kGridLayerFile, {pgm});
    m.files.push_back(entry("grid", prefix + kGridLayerFile, pgm));
    const std::string yaml = gridRosYaml(kGridLayerFile, static_cast<float>(params.grid.resolution_m),
                                         m.grid_origin_x, m.grid_origin_y);
    writeSynced(dir / kGridYamlLayerFile, {yaml});
    m.files.push_back(entry("grid_yaml", prefix + kGridYamlLayerFile, yaml));
    // A large grid: its overview and tile index too (map/grid_tiles.h).
    m.tiling = gridTiling(m.grid_width, m.grid_height, params.tiling);
    if (m.tiling.tiled()) {
      const std::vector<std::int8_t> overview = overviewCells(cells, m.tiling);
      m.grid_overview_cells_sha256 =
          sha256Hex({reinterpret_cast<const unsigned char*>(overview.data()), overview.size()});
      const std::string opgm = gridPgm(overview, m.tiling.overview_width, m.tiling.overview_height);
      writeSynced(dir / kGridOverviewLayerFile, {opgm});
      m.files.push_back(entry("grid_overview", prefix + kGridOverviewLayerFile, opgm));
      const std::string index =
          std::string(kGridTilesHeader) + "\n" + gridTileIndexText(gridTileIndex(cells, m.tiling));
      writeSynced(dir / kGridTilesLayerFile, {index});
      m.files.push_back(entry("grid_tiles", prefix + kGridTilesLayerFile, index));
    }
  }

  // The OctoMap before the cloud, so that the grid's raster (which it is made from when the fill
  // and resolution allow) is freed before the cloud's payload is built; its entry still follows
  // the cloud's in the manifest.
  const bool share = params.octomap.fill == OctomapExportParams::Fill::grid_columns &&
                     params.octomap.resolution_m == params.grid.resolution_m;
  if (!share) raster.reset();
  LayerFileEntry octomap_entry;
  {
    std::string bt;
    if (params.octomap.fill == OctomapExportParams::Fill::grid_columns) {
      if (!raster) {
        GridExportParams g = grid_params;
        g.resolution_m = params.octomap.resolution_m;
        raster = buildOccupancy(map, g);
      }
      OctomapSlabParams slab_params;
      slab_params.full_data = false;
      bt = octomapBinaryFile(encodeOctomapSlab(*raster, slab_params));
      raster.reset();
    } else {  // point_rays: the exporter writes map.bt (and map.ot, not a layer) into the directory
      exportOctomap(map, dir, "map", params.octomap);
      fs::remove(dir / "map.ot", ec);
      std::ifstream in(dir / kOctomapLayerFile, std::ios::binary);
      std::ostringstream ss;
      ss << in.rdbuf();
      bt = ss.str();
    }
    writeSynced(dir / kOctomapLayerFile, {bt});
    octomap_entry = entry("octomap", prefix + kOctomapLayerFile, bt);
  }

  {
    // A tiled grid: the cloud sorted along the same tiles, built in that order.
    TiledCloud cloud;
    if (m.tiling.tiled())
      cloud = tiledCloudPayload(map, m.tiling, params.grid.resolution_m, m.grid_origin_x, m.grid_origin_y);
    else
      cloud.data = cloudPayload(map);
    const std::vector<std::uint8_t>& data = cloud.data;
    m.cloud_points = data.size() / kCloudRecordBytes;
    const std::string header = cloudPcdHeader(m.cloud_points);
    writeSynced(dir / kCloudLayerFile, {header, {reinterpret_cast<const char*>(data.data()), data.size()}});
    Sha256 sha;
    sha.update(header);
    sha.update({data.data(), data.size()});
    m.files.push_back({"cloud", prefix + kCloudLayerFile, header.size() + data.size(), sha.hexDigest()});
    if (m.tiling.tiled()) {
      m.cloud_data_sha256 = sha256Hex({data.data(), data.size()});
      const std::string index = std::string(kCloudTilesHeader) + "\n" + cloudTileIndexText(cloud.tiles);
      writeSynced(dir / kCloudTilesLayerFile, {index});
      m.files.push_back(entry("cloud_tiles", prefix + kCloudTilesLayerFile, index));
    }
  }
  m.files.push_back(std::move(octomap_entry));
  return m;
}

std::string layersManifestText(const MapLayersManifest& l) {
  std::ostringstream m;
  const auto& p = l.params;
  m << "layers:\n"
    << "  grid_resolution_m: " << mapcodec::exactDouble(p.grid.resolution_m) << "\n"
    << "  grid_margin_m: " << mapcodec::exactDouble(p.grid.margin_m) << "\n"
    << "  grid_log_odds_hit: " << mapcodec::exactDouble(p.grid.log_odds_hit) << "\n"
    << "  grid_log_odds_miss: " << mapcodec::exactDouble(p.grid.log_odds_miss) << "\n"
    << "  grid_log_odds_clamp: " << mapcodec::exactDouble(p.grid.log_odds_clamp) << "\n"
    << "  octomap_fill: " << fillName(p.octomap.fill) << "\n"
    << "  octomap_resolution_m: " << mapcodec::exactDouble(p.octomap.resolution_m) << "\n"
    << "  octomap_max_range_m: " << mapcodec::exactDouble(p.octomap.max_range_m) << "\n"
    << "  grid_tile_cells: " << p.tiling.tile_cells << "\n"
    << "  grid_tile_above_cells: " << p.tiling.tile_above_cells << "\n"
    << "  grid_overview_max_cells: " << p.tiling.overview_max_cells << "\n"
    << "  grid_width: " << l.grid_width << "\n"
    << "  grid_height: " << l.grid_height << "\n"
    << "  grid_origin_x: " << mapcodec::exactDouble(l.grid_origin_x) << "\n"
    << "  grid_origin_y: " << mapcodec::exactDouble(l.grid_origin_y) << "\n"
    << "  grid_cells_sha256: " << mapcodec::yamlQuoted(l.grid_cells_sha256) << "\n";
  if (l.tiling.tiled())
    m << "  grid_overview_cells_sha256: " << mapcodec::yamlQuoted(l.grid_overview_cells_sha256) << "\n";
  m << "  cloud_points: " << l.cloud_points << "\n";
  if (l.tiling.tiled()) m << "  cloud_data_sha256: " << mapcodec::yamlQuoted(l.cloud_data_sha256) << "\n";
  m << "  files:\n";
  for (const auto& f : l.files)
    m << "    " << f.key << ":\n"
      << "      name: " << mapcodec::yamlQuoted(f.name) << "\n"
      << "      bytes: " << f.bytes << "\n"
      << "      sha256: " << mapcodec::yamlQuoted(f.sha256) << "\n";
  return m.str();
}

std::optional<MapLayersManifest> parseLayersManifest(const YamlParams& manifest, const std::string& origin) {
  if (!manifest.has("layers")) return std::nullopt;
  const YamlParams y = manifest.section("layers");
  MapLayersManifest l;
  // Saved before tiling existed (no grid_tile_cells key): never tiled.
  if (!y.has("grid_tile_cells")) l.params.tiling.tile_above_cells = static_cast<std::size_t>(1e12);
  loadParams(y, l.params);
  unsigned w = 0, h = 0;
  y.get("grid_width", w);
  y.get("grid_height", h);
  if (w == 0 || h == 0 || static_cast<std::uint64_t>(w) * h > kMaxLayerGridCells)
    throw InputError(origin, "layers: grid_width/grid_height missing or out of range");
  l.grid_width = w;
  l.grid_height = h;
  y.get("grid_origin_x", l.grid_origin_x);
  y.get("grid_origin_y", l.grid_origin_y);
  if (!std::isfinite(l.grid_origin_x) || !std::isfinite(l.grid_origin_y))
    throw InputError(origin, "layers: grid origin is not finite");
  y.get("grid_cells_sha256", l.grid_cells_sha256);
  if (!l.grid_cells_sha256.empty() && !isSha256Hex(l.grid_cells_sha256))
    throw InputError(origin, "layers.grid_cells_sha256: expected 64 lower-case hex digits");
  l.tiling = gridTiling(w, h, l.params.tiling);
  if (l.tiling.tiled()) {
    y.get("grid_overview_cells_sha256", l.grid_overview_cells_sha256);
    if (!isSha256Hex(l.grid_overview_cells_sha256))
      throw InputError(origin,
                       "layers.grid_overview_cells_sha256: expected 64 lower-case hex digits (a tiled grid)");
  }
  std::string points = "0";
  y.get("cloud_points", points);
  const auto n = parseCount(points);
  if (!n || *n > 0xffffffffULL) throw InputError(origin, "layers.cloud_points: expected an integer < 2^32");
  l.cloud_points = *n;
  if (l.tiling.tiled()) {
    y.get("cloud_data_sha256", l.cloud_data_sha256);
    if (!isSha256Hex(l.cloud_data_sha256))
      throw InputError(origin, "layers.cloud_data_sha256: expected 64 lower-case hex digits (a tiled map)");
  }
  const YamlParams files = y.section("files");
  std::vector<std::pair<const char*, const char*>> keys{{"grid", kGridLayerFile},
                                                        {"grid_yaml", kGridYamlLayerFile}};
  if (l.tiling.tiled())
    keys.insert(keys.end(), {{"grid_overview", kGridOverviewLayerFile}, {"grid_tiles", kGridTilesLayerFile}});
  keys.emplace_back("cloud", kCloudLayerFile);
  if (l.tiling.tiled()) keys.emplace_back("cloud_tiles", kCloudTilesLayerFile);
  keys.emplace_back("octomap", kOctomapLayerFile);
  for (const auto& [key, name] : keys) {
    const YamlParams f = files.section(key);
    LayerFileEntry e;
    e.key = key;
    std::string bytes;
    f.get("name", e.name);
    f.get("bytes", bytes);
    f.get("sha256", e.sha256);
    const auto size = parseCount(bytes);
    if (e.name != std::string(kLayersDir) + "/" + name || e.sha256.size() != 64 || !size)
      throw InputError(origin, std::string("layers.files.") + key + ": name (" + kLayersDir + "/" + name +
                                   "), bytes and sha256 required");
    e.bytes = *size;
    l.files.push_back(e);
  }
  return l;
}

}  // namespace radarslam
