// MRPT's object layout (mrpt/serialization CArchive::WriteObject): one byte 0x80 | name length
// (old format, MRPT < 0.5.5: a uint32 length), the class name (at most 120 bytes), the version
// (one byte; old format an int32; none for "nullptr"), the body, and the end flag 0x88 (not in
// the old format). CSensoryFrame's body: [uint32 frame id, versions < 2] uint32 n, n objects.
#include "rawlog_entries.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"

namespace radarslam::io_detail {

namespace {

constexpr std::uint8_t kEndFlag = 0x88;     // MRPT's SERIALIZATION_END_FLAG
constexpr std::size_t kMaxClassName = 120;  // MRPT's own bound
const std::string kNullptr = "nullptr";

const std::string& scanClass() {
  static const std::string name = CObservationRadarScan::GetRuntimeClassIdStatic().className;
  return name;
}
const std::string& frameClass() {
  static const std::string name = mrpt::obs::CSensoryFrame::GetRuntimeClassIdStatic().className;
  return name;
}

// A gz (or plain) input stream that counts the uncompressed bytes consumed and can hand bytes
// already read (an object header) out once more, so that MRPT reads an allowed object whole.
class ReplayGzInput : public mrpt::io::CStream {
 public:
  explicit ReplayGzInput(const std::filesystem::path& file) {
    requireRegularFile(file, "cannot open rawlog: file not found");
    std::string err;
    if (!gz_.open(file.string(), err)) throw InputError(file.string(), "cannot open rawlog: " + err);
  }
  size_t Read(void* buffer, size_t count) override {
    auto* out = static_cast<std::uint8_t*>(buffer);
    size_t n = 0;
    while (n < count && replay_at_ < replay_.size()) out[n++] = replay_[replay_at_++];
    if (n < count) {
      const size_t m = gz_.Read(out + n, count - n);
      consumed_ += m;
      n += m;
    }
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
  void replay(std::vector<std::uint8_t> bytes) {
    replay_ = std::move(bytes);
    replay_at_ = 0;
  }

 private:
  mrpt::io::CFileGZInputStream gz_;
  std::vector<std::uint8_t> replay_;
  std::size_t replay_at_ = 0;
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

struct ObjectHeader {
  std::string class_name;
  bool old_format = false;
  std::uint8_t version = 0;
  std::vector<std::uint8_t> bytes;  ///< as read, to replay for MRPT
};

}  // namespace

struct RawlogEntryStream::Impl {
  std::filesystem::path file;
  ReplayGzInput in;
  std::size_t entry = 0;

  explicit Impl(const std::filesystem::path& f) : file(f), in(f) {}

  [[noreturn]] void truncated() const {
    throw InputError(file.string(), "truncated rawlog: entry " + std::to_string(entry) +
                                        " ends early (after " + std::to_string(in.consumed()) +
                                        " uncompressed bytes)");
  }
  [[noreturn]] void corrupt(const std::string& problem) const {
    throw InputError(file.string(), "corrupt rawlog at entry " + std::to_string(entry) + ": " + problem);
  }
  [[noreturn]] void refuse(const std::string& class_name) const {
    if (!mrpt::rtti::findRegisteredClass(class_name)) corrupt("unknown class '" + class_name + "'");
    throw InputError(file.string(),
                     "entry " + std::to_string(entry) + " is a " + class_name + ": radarslam reads only " +
                         scanClass() + " (alone or in " + frameClass() +
                         ") and deserialises no other class; keep the radar's observations with "
                         "rawlog-edit --keep-label LABEL");
  }

  void readExactly(void* p, std::size_t n) {
    if (in.Read(p, n) != n) truncated();
  }

  /// nullopt if no byte is left where an entry may start (clean end of file).
  std::optional<ObjectHeader> readHeader(bool entry_may_end_here) {
    std::uint8_t first = 0;
    if (in.Read(&first, 1) == 0) {
      if (entry_may_end_here) return std::nullopt;
      truncated();
    }
    ObjectHeader h;
    h.bytes.push_back(first);
    auto take = [&](std::size_t n) {
      const std::size_t at = h.bytes.size();
      h.bytes.resize(at + n);
      readExactly(h.bytes.data() + at, n);
      return h.bytes.data() + at;
    };
    h.old_format = (first & 0x80) == 0;
    if (h.old_format) {
      const auto* rest = take(3);
      if (rest[0] || rest[1] || rest[2])
        corrupt("not an MRPT object header (byte " + std::to_string(first) + ")");
    }
    const std::size_t name_length = first & 0x7F;
    if (name_length > kMaxClassName) corrupt("class name of " + std::to_string(name_length) + " bytes");
    const auto* name = take(name_length);
    h.class_name.assign(reinterpret_cast<const char*>(name), name_length);
    if (h.old_format) {
      std::int32_t version = 0;
      std::memcpy(&version, take(4), 4);
      if (version < 0 || version >= 255) corrupt("object version " + std::to_string(version));
      h.version = static_cast<std::uint8_t>(version);
    } else if (h.class_name != kNullptr) {
      h.version = *take(1);
    }
    return h;
  }

  void readEndFlag(const ObjectHeader& h) {
    if (h.old_format) return;
    std::uint8_t flag = 0;
    readExactly(&flag, 1);
    if (flag != kEndFlag) corrupt("end-of-object flag missing after a " + h.class_name);
  }

  CObservationRadarScan::Ptr readScan(ObjectHeader h) {
    auto scan = CObservationRadarScan::Create();
    in.replay(std::move(h.bytes));
    try {
      mrpt::serialization::archiveFrom(in).ReadObject(scan.get());
    } catch (const std::exception& e) {
      if (in.hitEnd()) truncated();
      corrupt(mrptMessage(e));
    }
    return scan;
  }

  // CSensoryFrame::serializeFrom, versions 1 and 2, without its resize(n) of the count in the file.
  void readFrame(const ObjectHeader& h, std::vector<CObservationRadarScan::Ptr>& scans) {
    if (h.version == 0 || h.version > 2) corrupt(frameClass() + " version " + std::to_string(h.version));
    if (h.version < 2) {
      std::uint32_t frame_id = 0;  // dropped in version 2
      readExactly(&frame_id, 4);
    }
    std::uint32_t n = 0;
    readExactly(&n, 4);
    for (std::uint32_t i = 0; i < n; ++i)  // each object consumes bytes: n is bounded by the file
      readAllowed(*readHeader(false), scans, false);
    readEndFlag(h);
  }

  /// The allow-list: the object `h` heads is read (its scans appended) or refused. A frame is
  /// allowed at the top level only (MRPT's frames hold observations, not frames).
  void readAllowed(ObjectHeader h, std::vector<CObservationRadarScan::Ptr>& scans, bool frame_allowed) {
    if (h.class_name == scanClass())
      scans.push_back(readScan(std::move(h)));
    else if (frame_allowed && h.class_name == frameClass())
      readFrame(h, scans);
    else if (h.class_name == kNullptr)
      readEndFlag(h);
    else
      refuse(h.class_name);
  }
};

RawlogEntryStream::RawlogEntryStream(const std::filesystem::path& file)
    : impl_(std::make_unique<Impl>(file)) {}
RawlogEntryStream::~RawlogEntryStream() = default;

std::size_t RawlogEntryStream::ordinal() const { return impl_->entry; }

std::optional<std::vector<CObservationRadarScan::Ptr>> RawlogEntryStream::next() {
  auto header = impl_->readHeader(true);
  if (!header) return std::nullopt;
  std::vector<CObservationRadarScan::Ptr> scans;
  impl_->readAllowed(std::move(*header), scans, true);
  ++impl_->entry;
  return scans;
}

}  // namespace radarslam::io_detail
