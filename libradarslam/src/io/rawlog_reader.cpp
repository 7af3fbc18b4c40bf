// MRPT .rawlog files holding CObservationRadarScan objects (directly, or inside
// CSensoryFrames). Streaming: the file is read once at open to index the scans (object ordinal +
// reference time), keeping no scan; readScan() decompresses forward from the current position
// (sequential access costs one object each) and re-opens the file to go backwards. gzip streams
// cannot seek, hence no byte-offset index.
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <mutex>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"
#include "radarslam/obs/registration.h"
#include "readers.h"

namespace radarslam::io_detail {

namespace {

// A gz input stream that counts the uncompressed bytes consumed, so that an end of file at an
// object boundary (clean end) can be told from one inside an object (truncated file).
class CountingGzInput : public mrpt::io::CStream {
 public:
  explicit CountingGzInput(const std::filesystem::path& file) {
    requireRegularFile(file, "cannot open rawlog: file not found");
    std::string err;
    if (!gz_.open(file.string(), err)) throw InputError(file.string(), "cannot open rawlog: " + err);
  }
  size_t Read(void* buffer, size_t count) override {
    const size_t n = gz_.Read(buffer, count);
    consumed_ += n;
    if (n < count) hit_end_ = true;
    return n;
  }
  size_t Write(const void*, size_t) override { throw std::runtime_error("read-only stream"); }
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override { throw std::runtime_error("not seekable"); }
  uint64_t getTotalBytesCount() const override { return gz_.getTotalBytesCount(); }
  uint64_t getPosition() const override { return consumed_; }
  uint64_t consumed() const { return consumed_; }
  /// True once a read came back short (end of the data, or of a truncated gzip stream).
  bool hitEnd() const { return hit_end_; }

 private:
  mrpt::io::CFileGZInputStream gz_;
  uint64_t consumed_ = 0;
  bool hit_end_ = false;
};

// MRPT exceptions are multi-line reports with nested "Message:" lines; keep the innermost one.
std::string mrptMessage(const std::exception& e) {
  const std::string what = e.what();
  const auto pos = what.rfind("Message:");
  std::string line = pos == std::string::npos ? what : what.substr(pos + 8);
  line = line.substr(0, line.find('\n'));
  const auto first = line.find_first_not_of(' ');
  return first == std::string::npos ? line : line.substr(first);
}

class RawlogCursor {
 public:
  explicit RawlogCursor(const std::filesystem::path& file) : file_(file), in_(file) {}
  /// The next object, or nullptr at a clean end of file. Throws InputError if truncated/corrupt.
  mrpt::serialization::CSerializable::Ptr next() {
    const uint64_t before = in_.consumed();
    try {
      auto obj = mrpt::serialization::archiveFrom(in_).ReadObject();
      ++ordinal_;
      return obj;
    } catch (const mrpt::serialization::CExceptionEOF& e) {
      if (in_.consumed() == before) return nullptr;
      throw InputError(file_.string(), "truncated rawlog: entry " + std::to_string(ordinal_) +
                                           " ends early (after " + std::to_string(in_.consumed()) +
                                           " uncompressed bytes)");
    } catch (const std::exception& e) {
      if (in_.hitEnd())
        throw InputError(file_.string(), "truncated rawlog: entry " + std::to_string(ordinal_) +
                                             " ends early (after " + std::to_string(in_.consumed()) +
                                             " uncompressed bytes)");
      throw InputError(file_.string(),
                       "corrupt rawlog at entry " + std::to_string(ordinal_) + ": " + mrptMessage(e));
    }
  }
  std::size_t ordinal() const { return ordinal_; }  ///< number of objects read so far

 private:
  std::filesystem::path file_;
  CountingGzInput in_;
  std::size_t ordinal_ = 0;
};

// The radar scans an entry holds (a scan itself, or those in a sensory frame).
std::vector<CObservationRadarScan::Ptr> radarScansOf(const mrpt::serialization::CSerializable::Ptr& obj) {
  std::vector<CObservationRadarScan::Ptr> out;
  if (auto s = std::dynamic_pointer_cast<CObservationRadarScan>(obj))
    out.push_back(s);
  else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
    for (const auto& o : *sf)
      if (auto r = std::dynamic_pointer_cast<CObservationRadarScan>(o)) out.push_back(r);
  return out;
}

class RawlogReader : public DatasetReader {
 public:
  explicit RawlogReader(const std::filesystem::path& file) : file_(file) {
    registerRadarslamClasses();
    RawlogCursor cursor(file);
    std::size_t objects = 0;
    while (auto obj = cursor.next()) {
      const auto scans = radarScansOf(obj);
      for (std::size_t j = 0; j < scans.size(); ++j) {
        entries_.push_back({objects, j, scans[j]->refStampNs()});
        if (label_.empty()) label_ = scans[j]->sensorLabel;
      }
      ++objects;
    }
    if (entries_.empty())
      throw InputError(file.string(), "no radar scans (CObservationRadarScan) in the rawlog (" +
                                          std::to_string(objects) + " other entries)");
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
    const bool have_current = cursor_ && current_ && cursor_->ordinal() == e.object + 1;
    if (!have_current) {
      if (!cursor_ || cursor_->ordinal() > e.object) cursor_ = std::make_unique<RawlogCursor>(file_);
      current_.reset();
      while (cursor_->ordinal() <= e.object) {
        current_ = cursor_->next();
        if (!current_) throw InputError(file_.string(), "rawlog changed since it was opened (fewer entries)");
      }
    }
    const auto scans = radarScansOf(current_);
    if (e.sub >= scans.size()) throw InputError(file_.string(), "rawlog changed since it was opened");
    if (std::dynamic_pointer_cast<CObservationRadarScan>(current_)) {
      current_.reset();  // handed out as is; asking again re-reads it
      return scans[0];
    }
    // A sensory frame may be asked for its other scans: keep it and hand out copies.
    return std::make_shared<CObservationRadarScan>(*scans[e.sub]);
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
  mutable std::unique_ptr<RawlogCursor> cursor_;
  mutable mrpt::serialization::CSerializable::Ptr current_;
};

}  // namespace

std::unique_ptr<DatasetReader> openRawlog(const std::filesystem::path& file) {
  return std::make_unique<RawlogReader>(file);
}

}  // namespace radarslam::io_detail
