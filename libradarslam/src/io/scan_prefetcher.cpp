#include "scan_prefetcher.h"

#include <algorithm>

namespace radarslam::io_detail {

FetchedScan fetchScan(const DatasetReader& reader, std::size_t i) {
  FetchedScan f;
  try {
    f.scan = reader.readScan(i);
    f.inconsistency = f.scan->checkConsistency();
    f.blank = std::all_of(f.scan->power.begin(), f.scan->power.end(), [](std::uint8_t p) { return p == 0; });
  } catch (...) {
    f.scan.reset();
    f.error = std::current_exception();
  }
  return f;
}

ScanPrefetcher::ScanPrefetcher(const DatasetReader& reader, std::size_t first, std::size_t end,
                               std::size_t depth)
    : reader_(reader), depth_(std::max<std::size_t>(depth, 1)) {
  worker_ = std::thread([this, first, end] { run(first, end); });
}

ScanPrefetcher::~ScanPrefetcher() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  space_.notify_all();
  worker_.join();
}

void ScanPrefetcher::run(std::size_t first, std::size_t end) {
  for (std::size_t i = first; i < end; ++i) {
    {
      std::unique_lock lock(mutex_);
      space_.wait(lock, [&] { return stop_ || items_.size() < depth_; });
      if (stop_) return;
    }
    FetchedScan f = fetchScan(reader_, i);  // outside the lock: this is the work
    std::lock_guard lock(mutex_);
    items_.push_back(std::move(f));
    ready_.notify_one();
  }
}

FetchedScan ScanPrefetcher::take() {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, [&] { return !items_.empty(); });
  FetchedScan f = std::move(items_.front());
  items_.pop_front();
  space_.notify_one();
  return f;
}

}  // namespace radarslam::io_detail
