#include "radarslam/io/rawlog_writer.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CArchive.h>

#include "radarslam/core/errors.h"

namespace radarslam {

struct RawlogWriter::Impl {
  mrpt::io::CFileGZOutputStream out;
};

RawlogWriter::RawlogWriter(const std::filesystem::path& file, int gzip_level)
    : impl_(std::make_unique<Impl>()), file_(file) {
  if (!impl_->out.open(file.string(), gzip_level)) throw InputError(file.string(), "cannot open for writing");
}

RawlogWriter::~RawlogWriter() = default;

void RawlogWriter::write(const CObservationRadarScan& scan) {
  if (!impl_->out.fileOpenCorrectly()) throw InputError(file_.string(), "rawlog already closed");
  try {
    mrpt::serialization::archiveFrom(impl_->out).WriteObject(scan);
  } catch (const std::exception& e) {
    std::string what = e.what();
    throw InputError(file_.string(), "write failed: " + what.substr(0, what.find('\n')));
  }
  ++count_;
}

void RawlogWriter::close() { impl_->out.close(); }

}  // namespace radarslam
