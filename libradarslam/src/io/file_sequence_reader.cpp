#include <algorithm>
#include <string>

#include "radarslam/core/errors.h"
#include "readers.h"
#include "text_util.h"

namespace radarslam::io_detail {

FileSequenceReader::FileSequenceReader(DatasetKind kind, std::filesystem::path root,
                                       std::vector<IndexEntry> index)
    : kind_(kind), root_(std::move(root)), index_(std::move(index)) {
  // The sequence's image size comes from its first readable scan (headers only, no decoding).
  for (std::size_t i = 0; i < std::min<std::size_t>(index_.size(), 8); ++i) {
    try {
      expected_size_ = readPngSize(index_[i].file);
      expected_size_file_ = index_[i].file;
      break;
    } catch (const InputError&) {
      // a missing/corrupt scan is reported when it is read
    }
  }
}

const IndexEntry& FileSequenceReader::entry(std::size_t i) const {
  if (i >= index_.size())
    throw InputError(root_.string(), "scan index " + std::to_string(i) + " out of range (" +
                                         std::to_string(index_.size()) + " scans)");
  return index_[i];
}

std::optional<std::size_t> FileSequenceReader::findFile(const std::filesystem::path& file) const {
  const auto name = file.filename();
  for (std::size_t i = 0; i < index_.size(); ++i)
    if (index_[i].file.filename() == name) return i;
  return std::nullopt;
}

cv::Mat FileSequenceReader::readImage(std::size_t i) const {
  const auto& e = entry(i);
  cv::Mat img = readGreyPng(e.file);
  if (expected_size_ && (img.cols != expected_size_->width || img.rows != expected_size_->height))
    throw InputError(e.file.string(), "image is " + std::to_string(img.cols) + "x" +
                                          std::to_string(img.rows) + " (WxH) but this sequence's scans are " +
                                          std::to_string(expected_size_->width) + "x" +
                                          std::to_string(expected_size_->height) + " (as " +
                                          expected_size_file_.filename().string() + ")");
  return img;
}

StampNs FileSequenceReader::frameInterval(std::size_t i, StampNs fallback) const {
  if (index_.size() < 2) return fallback;
  if (i + 1 < index_.size()) return index_[i + 1].stamp - index_[i].stamp;
  return index_[i].stamp - index_[i - 1].stamp;
}

std::vector<IndexEntry> listStampedFiles(const std::filesystem::path& dir, const std::string& ext) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw InputError(dir.string(), "directory not found");
  std::vector<IndexEntry> out;
  for (const auto& de : std::filesystem::directory_iterator(dir)) {
    if (!de.is_regular_file() || de.path().extension() != ext) continue;
    IndexEntry e;
    e.file = de.path();
    e.stamp = parseStamp(de.path().stem().string(), de.path().string(), "file name");
    out.push_back(std::move(e));
  }
  if (out.empty()) throw InputError(dir.string(), "no *" + ext + " scan files");
  std::sort(out.begin(), out.end(),
            [](const IndexEntry& a, const IndexEntry& b) { return a.stamp < b.stamp; });
  for (std::size_t i = 1; i < out.size(); ++i)
    if (out[i].stamp == out[i - 1].stamp)
      throw InputError(out[i].file.string(), "same timestamp as " + out[i - 1].file.filename().string());
  return out;
}

}  // namespace radarslam::io_detail
