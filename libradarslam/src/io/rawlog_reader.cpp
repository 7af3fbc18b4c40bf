// MRPT .rawlog files holding CObservationRadarScan objects (directly, or inside
// CSensoryFrames). Streaming: the file is read once at open to index the scans (object ordinal +
// reference time), keeping no scan; readScan() decompresses forward from the current position
// (sequential access costs one object each) and re-opens the file to go backwards. gzip streams
// cannot seek, hence no byte-offset index. The entries are parsed by RawlogEntryStream, which
// deserialises no class outside an allow-list (rawlog_entries.h).
#include <mutex>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/obs/registration.h"
#include "rawlog_entries.h"
#include "readers.h"

namespace radarslam::io_detail {

namespace {

class RawlogReader : public DatasetReader {
 public:
  explicit RawlogReader(const std::filesystem::path& file) : file_(file) {
    registerRadarslamClasses();
    RawlogEntryStream stream(file);
    while (const auto scans = stream.next())
      for (std::size_t j = 0; j < scans->size(); ++j) {
        entries_.push_back({stream.ordinal() - 1, j, (*scans)[j]->refStampNs()});
        if (label_.empty()) label_ = (*scans)[j]->sensorLabel;
      }
    if (entries_.empty())
      throw InputError(file.string(), "no radar scans (CObservationRadarScan) in the rawlog (" +
                                          std::to_string(stream.ordinal()) + " empty entries)");
  }
  DatasetKind kind() const override { return DatasetKind::Rawlog; }
  const std::filesystem::path& root() const override { return file_; }
  std::string sensorName() const override { return label_.empty() ? "radar (rawlog)" : label_ + " (rawlog)"; }
  std::size_t size() const override { return entries_.size(); }
  StampNs indexStamp(std::size_t i) const override { return at(i).stamp; }
  std::filesystem::path scanPath(std::size_t) const override { return file_; }
  const Trajectory& groundTruth() const override { return ground_truth_; }

  CObservationRadarScan::Ptr readScan(std::size_t i) const override {
    const Entry& e = at(i);
    std::lock_guard lock(mutex_);
    const bool have_current = stream_ && current_ && stream_->ordinal() == e.object + 1;
    if (!have_current) {
      if (!stream_ || stream_->ordinal() > e.object) stream_ = std::make_unique<RawlogEntryStream>(file_);
      current_.reset();
      while (stream_->ordinal() <= e.object) {
        current_ = stream_->next();
        if (!current_) throw InputError(file_.string(), "rawlog changed since it was opened (fewer entries)");
      }
    }
    if (e.sub >= current_->size()) throw InputError(file_.string(), "rawlog changed since it was opened");
    if (current_->size() == 1) {
      auto scan = (*current_)[0];
      current_.reset();  // handed out as is; asking again re-reads it
      return scan;
    }
    // A sensory frame may be asked for its other scans: keep it and hand out copies.
    return std::make_shared<CObservationRadarScan>(*(*current_)[e.sub]);
  }

 private:
  struct Entry {
    std::size_t object = 0, sub = 0;
    StampNs stamp = 0;
  };
  const Entry& at(std::size_t i) const {
    if (i >= entries_.size())
      throw InputError(file_.string(), "scan index " + std::to_string(i) + " out of range (" +
                                           std::to_string(entries_.size()) + " scans)");
    return entries_[i];
  }

  std::filesystem::path file_;
  std::string label_;
  std::vector<Entry> entries_;
  Trajectory ground_truth_;
  mutable std::mutex mutex_;
  mutable std::unique_ptr<RawlogEntryStream> stream_;
  mutable std::optional<std::vector<CObservationRadarScan::Ptr>> current_;  ///< the last entry read
};

}  // namespace

std::unique_ptr<DatasetReader> openRawlog(const std::filesystem::path& file) {
  return std::make_unique<RawlogReader>(file);
}

}  // namespace radarslam::io_detail
