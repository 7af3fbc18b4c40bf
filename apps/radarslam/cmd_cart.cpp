// `radarslam cart PATH OUT.png`: one radar scan as a Cartesian image (optionally with the
// Algorithm-1 peak cloud drawn over it), for looking at data and checking a dataset's geometry.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include <radarslam/core/atomic_file.h>
#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/core/output_path.h>
#include <radarslam/io/dataset.h>
#include <radarslam/radar/cartesian.h>
#include <radarslam/radar/peak_cloud.h>

#include "cli_common.h"
#include "command.h"

namespace radarslam::cli {
namespace {

int runCart(int argc, char** argv) {
  CommandLine cmd("cart",
                  "Writes one radar scan as a Cartesian image (sensor at the centre, +x up, +y right). "
                  "PATH is a dataset directory or .rawlog (scan --index) or a single scan file.");
  TCLAP::UnlabeledValueArg<std::string> path_arg("path", "Dataset directory, .rawlog or scan file", true, "",
                                                 "PATH", cmd.tclap());
  TCLAP::UnlabeledValueArg<std::string> out_arg("out", "Output image (.png)", true, "", "OUT", cmd.tclap());
  TCLAP::ValueArg<long long> index_arg("", "index", "Scan index in the dataset (0-based)", false, 0, "N",
                                       cmd.tclap());
  TCLAP::ValueArg<int> size_arg("", "size", "Image side in pixels", false, CartesianParams{}.size_px, "PX",
                                cmd.tclap());
  TCLAP::ValueArg<double> res_arg("", "resolution", "Metres per pixel", false, CartesianParams{}.m_per_px,
                                  "M_PER_PX", cmd.tclap());
  TCLAP::SwitchArg peaks_arg("", "peaks", "Overlay the Algorithm-1 peak point cloud in red", cmd.tclap());
  cmd.parse(argc, argv);

  const std::string where = "radarslam cart";
  if (size_arg.getValue() <= 0 || size_arg.getValue() > 20000)
    throw InputError(where, "--size must be in 1..20000 (got " + std::to_string(size_arg.getValue()) + ")");
  if (!(res_arg.getValue() >= 0.001 && res_arg.getValue() <= 100))
    throw InputError(where, "--resolution must be in [0.001, 100] m/px");
  if (index_arg.getValue() < 0) throw InputError(where, "--index must be >= 0");

  const std::filesystem::path path = path_arg.getValue(), out = out_arg.getValue();
  if (!std::filesystem::exists(path)) throw InputError(path.string(), "no such file or directory");
  checkNoOverlap(path, out);
  checkFileOutput(out, "OUT");
  std::string ext = out.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png") throw InputError(out.string(), "output must be a .png file");

  CObservationRadarScan::Ptr scan;
  if (std::filesystem::is_directory(path) || path.extension() == ".rawlog") {
    const auto reader = openDataset(path);
    const auto index = static_cast<std::size_t>(index_arg.getValue());
    if (index >= reader->size())
      throw InputError(path.string(), "scan index " + std::to_string(index) + " out of range (" +
                                          std::to_string(reader->size()) + " scans)");
    scan = reader->readScan(index);
  } else {
    if (index_arg.isSet())
      throw InputError(where, "--index needs a dataset directory or .rawlog, not a scan file");
    scan = readScanFile(path);
  }

  CartesianParams params;
  params.size_px = size_arg.getValue();
  params.m_per_px = res_arg.getValue();
  const PolarToCartesian conv(params);
  cv::Mat img = conv.convert(*scan);

  std::size_t num_peaks = 0;
  if (peaks_arg.getValue()) {
    const auto cloud = extractPeakCloud(*scan);
    num_peaks = cloud.size();
    cv::cvtColor(img, img, cv::COLOR_GRAY2BGR);
    const int radius = std::max(1, params.size_px / 700);
    for (const RadarPoint& p : cloud)
      cv::circle(img, conv.metresToPixel(p.x, p.y), radius, cv::Scalar(0, 0, 255), cv::FILLED, cv::LINE_AA);
  }

  std::vector<unsigned char> png;
  if (!cv::imencode(".png", img, png)) throw InputError(out.string(), "PNG encoding failed");
  writeBytesAtomically(out, png);
  std::string peaks_note;
  if (peaks_arg.getValue()) peaks_note.append(", ").append(std::to_string(num_peaks)).append(" peaks");
  logger().logFmt(mrpt::system::LVL_INFO, "wrote %s (%dx%d px, %.3f m/px, %u azimuths x %u bins%s)",
                  out.string().c_str(), img.cols, img.rows, params.m_per_px, scan->num_azimuths,
                  scan->num_bins, peaks_note.c_str());
  return 0;
}

}  // namespace

RADARSLAM_COMMAND("cart", "Write a radar scan as a Cartesian image (optionally with its peak cloud)",
                  runCart);

}  // namespace radarslam::cli
