// RADIATE (Navtech CTS350-X): Navtech_Polar/<frame>.png, 576 rows = range bins x 400 columns =
// azimuths (column 0 = 0 deg), 0.173611 m/bin, one time per frame in Navtech_Polar.txt
// ("Frame: 000001 Time: <s>.<ns>"); no ground truth (FORMATS.md section 4).
//
// No per-azimuth times exist. We take the frame time as the MIDDLE of the sweep (so a scan's
// reference time, the mid-sweep, is exactly the dataset's frame time and the error of this
// guess is at most half a sweep whichever convention the recorder used) and spread the azimuths
// evenly over one sweep = the median interval between consecutive frames (robust to dropped frames).
//
// Navtech_Polar.txt is optional (a folder of the polar images alone): the frames are then indexed
// by their numbers (<frame>.png) and timed at the nominal 4 Hz, frame n at kNoTimesEpoch + (n - 1)
// * 250 ms. Absolute time, the real frame rate and gaps from dropped frames are then unknown.
#include <algorithm>
#include <map>
#include <string>

#include "polar_png.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "readers.h"
#include "text_util.h"

namespace radarslam::io_detail {

namespace {

std::vector<IndexEntry> readFrameTimes(const std::filesystem::path& root) {
  const auto file = root / "Navtech_Polar.txt";
  auto in = openText(file, "Navtech_Polar.txt (RADIATE frame times)");
  std::vector<IndexEntry> index;
  std::map<long long, StampNs> frame_times;  // frame number -> its time, to catch repeated lines
  std::size_t duplicates = 0;
  forEachDataLine(in, file, ' ', 0, [&](const DataLine& d) {
    const std::string& where = d.where;
    const auto& f = d.fields;
    StampNs t = 0;
    if (f.size() != 4 || f[0] != "Frame:" || f[2] != "Time:" ||
        !parseSecondsDotFraction(std::string(f[3]), t))
      throw InputError(where, "malformed line: expected 'Frame: <number> Time: <seconds>.<nanoseconds>'");
    const long long frame = parseInt(f[1], where, "frame number");
    if (const auto seen = frame_times.find(frame); seen != frame_times.end()) {
      if (seen->second != t)
        throw InputError(where, "frame " + std::string(f[1]) + " listed again with a different time");
      ++duplicates;  // the same line twice: read the frame once
      return;
    }
    frame_times.emplace(frame, t);
    if (!index.empty() && t <= index.back().stamp) throw InputError(where, "frame times are not increasing");
    index.push_back({t, root / "Navtech_Polar" / (std::string(f[1]) + ".png")});
  });
  if (index.empty()) throw InputError(file.string(), "no frames");
  if (duplicates > 0)
    logger().logFmt(mrpt::system::LVL_WARN,
                    "%s: %zu duplicate frame line(s) skipped (each frame is read once)",
                    file.string().c_str(), duplicates);
  return index;
}

// 2000-01-01 00:00:00 UTC: a plausible UNIX time, obviously not a real recording time.
constexpr StampNs kNoTimesEpoch = 946684800LL * kNsPerSec;

bool hasFrameTimes(const std::filesystem::path& root) {
  std::error_code ec;
  return std::filesystem::exists(root / "Navtech_Polar.txt", ec);
}

/// Navtech_Polar/<frame>.png by frame number (1-based, any zero padding), at the nominal 4 Hz.
std::vector<IndexEntry> frameNumberIndex(const std::filesystem::path& root) {
  const auto dir = root / "Navtech_Polar";
  std::vector<std::pair<long long, std::filesystem::path>> frames;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const auto& p = it->path();
    if (p.extension() != ".png") continue;
    const std::string stem = p.stem().string();
    if (stem.empty() || stem.size() > 9 || stem.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(p.string(), "RADIATE frame file name is not a frame number (<digits>.png)");
    frames.emplace_back(std::stoll(stem), p);
  }
  if (ec) throw InputError(dir.string(), "cannot list: " + ec.message());
  if (frames.empty()) throw InputError(dir.string(), "no *.png frames");
  std::sort(frames.begin(), frames.end());
  std::vector<IndexEntry> index;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0 && frames[i].first == frames[i - 1].first)
      throw InputError(frames[i].second.string(),
                       "same frame number as " + frames[i - 1].second.filename().string());
    index.push_back({kNoTimesEpoch + (frames[i].first - 1) * kNominalSweepNs, frames[i].second});
  }
  return index;
}

class RadiateReader : public FileSequenceReader {
 public:
  RadiateReader(const std::filesystem::path& root, const ReaderOptions& o)
      : RadiateReader(root, o, hasFrameTimes(root)) {}
  RadiateReader(const std::filesystem::path& root, const ReaderOptions& o, bool frame_times)
      : FileSequenceReader(DatasetKind::Radiate, root,
                           frame_times ? readFrameTimes(root) : frameNumberIndex(root)),
        frame_times_(frame_times) {
    resolution_ = o.range_resolution_m > 0 ? o.range_resolution_m : kRadiateResolution;
    offset_ = o.range_offset_m.value_or(resolution_ / 2);  // bin centres, as for Oxford's CTS350-X
    std::vector<StampNs> d;
    for (std::size_t i = 1; i < index_.size(); ++i) d.push_back(index_[i].stamp - index_[i - 1].stamp);
    if (!d.empty()) {
      std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
      sweep_ns_ = d[d.size() / 2];
    }
  }
  std::string sensorName() const override { return "Navtech CTS350-X"; }
  std::vector<std::string> missingParts() const override {
    if (frame_times_) return {};
    return {
        "Navtech_Polar.txt missing: frames timed by their numbers at the nominal 4 Hz from "
        "2000-01-01 (no absolute time; dropped frames and the real frame rate are not seen)"};
  }
  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    const cv::Mat img = readImage(i);
    return decodeTransposed(
        img, entry(i).file, resolution_, offset_,
        evenlySpacedStamps(static_cast<std::size_t>(img.cols), sweep_ns_, entry(i).stamp, 0.5));
  }

 private:
  bool frame_times_ = true;
  double resolution_ = kRadiateResolution;
  double offset_ = 0.0;
  StampNs sweep_ns_ = kNominalSweepNs;
};

}  // namespace

std::unique_ptr<DatasetReader> openRadiate(const std::filesystem::path& root, const ReaderOptions& o,
                                           OpenFlags) {
  return std::make_unique<RadiateReader>(root, o);
}

}  // namespace radarslam::io_detail
