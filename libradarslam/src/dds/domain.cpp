#include "radarslam/dds/domain.h"

#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "c_types.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/input_file.h"

namespace radarslam::dds {

const char* const kLoopbackConfigXml =
    "<CycloneDDS><Domain Id=\"any\"><General><Interfaces>"
    "<NetworkInterface name=\"lo\" multicast=\"false\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast>"
    "<MaxMessageSize>65000B</MaxMessageSize><FragmentSize>60000B</FragmentSize></General><Discovery>"
    "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>"
    "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>";

TimeMsg toTimeMsg(StampNs t) {
  StampNs sec = t / kNsPerSec, ns = t % kNsPerSec;
  if (ns < 0) {
    ns += kNsPerSec;
    --sec;
  }
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(ns)};
}
StampNs fromTimeMsg(const TimeMsg& t) { return static_cast<StampNs>(t.sec) * kNsPerSec + t.nanosec; }

std::string readConfigFile(const std::filesystem::path& path) {
  requireRegularFile(path, "cannot read the DDS configuration file (not found)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot read the DDS configuration file");
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string xml = ss.str();
  if (xml.find("<CycloneDDS") == std::string::npos)
    throw InputError(path.string(), "not a Cyclone DDS XML configuration (no <CycloneDDS> element)");
  return xml;
}

namespace {

std::string ddsError(dds_return_t rc) { return dds_strretcode(rc); }

[[noreturn]] void fail(const std::string& what, dds_return_t rc) {
  throw std::runtime_error("DDS: " + what + " failed: " + ddsError(rc));
}

// Explicit domains are per process; several Domain objects with the same id share one.
struct DomainRegistry {
  std::mutex mutex;
  std::map<std::uint32_t, std::pair<dds_entity_t, int>> domains;  // id -> (handle, users)
};
DomainRegistry& registry() {
  static DomainRegistry r;
  return r;
}

void captureLog(void* out, const dds_log_data_t* data) {
  static_cast<std::string*>(out)->append(data->message, data->size);
}

void releaseDomain(std::uint32_t id) {
  auto& reg = registry();
  std::lock_guard lock(reg.mutex);
  auto it = reg.domains.find(id);
  if (it != reg.domains.end() && --it->second.second == 0) {
    dds_delete(it->second.first);
    reg.domains.erase(it);
  }
}

struct Qos {
  dds_qos_t* q;
  explicit Qos(const TopicQos& t) : q(dds_create_qos()) {
    dds_qset_reliability(q, t.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                         DDS_SECS(10));
    dds_qset_durability(q, t.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    if (t.keep_all)
      dds_qset_history(q, DDS_HISTORY_KEEP_ALL, 0);
    else
      dds_qset_history(q, DDS_HISTORY_KEEP_LAST, t.depth);
    // What a transient-local writer keeps for late joiners is the durability service's history
    // (Cyclone 0.10: default KEEP_LAST 1, whatever the writer's own history): make it the same.
    if (t.transient_local)
      dds_qset_durability_service(q, 0, t.keep_all ? DDS_HISTORY_KEEP_ALL : DDS_HISTORY_KEEP_LAST,
                                  t.keep_all ? 0 : t.depth, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                                  DDS_LENGTH_UNLIMITED);
    const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
    dds_qset_data_representation(q, 1, xcdr1);
  }
  ~Qos() { dds_delete_qos(q); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
};

template <class Msg>
dds_entity_t createTopic(Domain& domain, const std::string& name, const TopicQos& qos) {
  Qos q(qos);
  const dds_entity_t t =
      dds_create_topic(domain.participant(), detail::CType<Msg>::descriptor(), name.c_str(), q.q, nullptr);
  if (t < 0) fail("creating topic " + name, t);
  return t;
}

}  // namespace

Domain::Domain(std::uint32_t domain_id, const std::string& config_xml) : id_(domain_id) {
  const std::string where = "DDS domain " + std::to_string(domain_id);
  if (domain_id > kMaxDomainId)
    throw InputError(where, "domain id must be 0.." + std::to_string(kMaxDomainId));
  {
    auto& reg = registry();
    std::lock_guard lock(reg.mutex);
    auto it = reg.domains.find(domain_id);
    if (it == reg.domains.end()) {
      // Cyclone reports configuration problems through its log (stderr by default): capture them
      // so the error is one line naming the problem.
      std::string log;
      dds_set_log_sink(&captureLog, &log);
      const dds_entity_t d = dds_create_domain(domain_id, config_xml.c_str());
      dds_set_log_sink(nullptr, nullptr);
      if (d < 0) {
        std::string reason = log.substr(0, log.find('\n'));
        if (reason.rfind("config: ", 0) == 0) reason.erase(0, 8);
        if (reason.empty()) reason = ddsError(d);
        throw InputError(where, "cannot create it from the configuration: " + reason);
      }
      it = reg.domains.emplace(domain_id, std::make_pair(d, 0)).first;
    }
    ++it->second.second;
    domain_ = it->second.first;
  }
  participant_ = dds_create_participant(domain_id, nullptr, nullptr);
  if (participant_ < 0) {
    const dds_return_t rc = participant_;
    releaseDomain(domain_id);
    throw InputError(where, "cannot create a participant (" + ddsError(rc) + ")");
  }
}

Domain::~Domain() {
  dds_delete(participant_);
  releaseDomain(id_);
}

// --- Publisher -----------------------------------------------------------------------------------
template <class Msg>
Publisher<Msg>::Publisher(Domain& domain, const std::string& topic, const TopicQos& qos) {
  topic_ = createTopic<Msg>(domain, topic, qos);
  Qos q(qos);
  writer_ = dds_create_writer(domain.participant(), topic_, q.q, nullptr);
  if (writer_ < 0) {
    const dds_return_t rc = writer_;
    dds_delete(topic_);
    fail("creating a writer on " + topic, rc);
  }
}

template <class Msg>
Publisher<Msg>::~Publisher() {
  dds_delete(writer_);
  dds_delete(topic_);
}

template <class Msg>
void Publisher<Msg>::publish(const Msg& msg) {
  typename detail::CType<Msg>::type c{};
  std::vector<sensor_msgs_msg_dds__PointField_> storage;
  detail::toC(msg, c, storage);
  const dds_return_t rc = dds_write(writer_, &c);
  if (rc < 0) fail("write", rc);
}

template <class Msg>
std::uint32_t Publisher<Msg>::matchedSubscriptions() const {
  dds_publication_matched_status_t st{};
  if (dds_get_publication_matched_status(writer_, &st) < 0) return 0;
  return st.current_count;
}

template <class Msg>
bool Publisher<Msg>::waitForSubscriptions(std::uint32_t count, std::chrono::milliseconds timeout) const {
  const dds_time_t deadline = dds_time() + DDS_MSECS(timeout.count());
  dds_set_status_mask(writer_, DDS_PUBLICATION_MATCHED_STATUS);
  const dds_entity_t ws = dds_create_waitset(dds_get_participant(writer_));
  dds_waitset_attach(ws, writer_, 0);
  bool ok = false;
  for (;;) {
    if (matchedSubscriptions() >= count) {
      ok = true;
      break;
    }
    if (dds_time() >= deadline) break;
    dds_waitset_wait_until(ws, nullptr, 0, deadline);
  }
  dds_delete(ws);
  return ok;
}

template <class Msg>
bool Publisher<Msg>::waitForAcknowledgements(std::chrono::milliseconds timeout) const {
  return dds_wait_for_acks(writer_, DDS_MSECS(timeout.count())) == DDS_RETCODE_OK;
}

// --- Subscription --------------------------------------------------------------------------------
template <class Msg>
Subscription<Msg>::Subscription(Domain& domain, const std::string& topic, const TopicQos& qos) {
  topic_ = createTopic<Msg>(domain, topic, qos);
  Qos q(qos);
  reader_ = dds_create_reader(domain.participant(), topic_, q.q, nullptr);
  if (reader_ < 0) {
    const dds_return_t rc = reader_;
    dds_delete(topic_);
    fail("creating a reader on " + topic, rc);
  }
  waitset_ = dds_create_waitset(domain.participant());
  condition_ = dds_create_readcondition(reader_, DDS_ANY_STATE);
  dds_waitset_attach(waitset_, condition_, 0);
}

template <class Msg>
Subscription<Msg>::~Subscription() {
  dds_delete(waitset_);
  dds_delete(condition_);
  dds_delete(reader_);
  dds_delete(topic_);
}

template <class Msg>
std::optional<Msg> Subscription<Msg>::take(std::chrono::milliseconds timeout) {
  const dds_time_t deadline = dds_time() + DDS_MSECS(timeout.count());
  for (;;) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    const dds_return_t n = dds_take(reader_, samples, &info, 1, 1);
    if (n < 0) fail("take", n);
    if (n > 0) {
      std::optional<Msg> out;
      if (info.valid_data)
        out = detail::fromC<Msg>(*static_cast<const typename detail::CType<Msg>::type*>(samples[0]));
      dds_return_loan(reader_, samples, n);
      if (out) return out;
      continue;  // an instance state change without data (e.g. the writer went away)
    }
    if (dds_time() >= deadline) return std::nullopt;
    dds_waitset_wait_until(waitset_, nullptr, 0, deadline);
  }
}

template <class Msg>
std::uint32_t Subscription<Msg>::matchedPublications() const {
  dds_subscription_matched_status_t st{};
  if (dds_get_subscription_matched_status(reader_, &st) < 0) return 0;
  return st.current_count;
}

// --- WaitSet -------------------------------------------------------------------------------------
WaitSet::WaitSet(Domain& domain) : waitset_(dds_create_waitset(domain.participant())) {
  if (waitset_ < 0) fail("creating a waitset", waitset_);
}
WaitSet::~WaitSet() { dds_delete(waitset_); }
void WaitSet::attachCondition(std::int32_t condition) {
  const dds_return_t rc = dds_waitset_attach(waitset_, condition, 0);
  if (rc < 0) fail("attaching to a waitset", rc);
}
bool WaitSet::wait(std::chrono::milliseconds timeout) {
  const dds_return_t n = dds_waitset_wait(waitset_, nullptr, 0, DDS_MSECS(timeout.count()));
  if (n < 0) fail("waiting", n);
  return n > 0;
}

template <class Msg>
std::string ddsTypeName() {
  return detail::CType<Msg>::descriptor()->m_typename;
}

#define RADARSLAM_DDS_INSTANTIATE(MSG) \
  template class Publisher<MSG>;       \
  template class Subscription<MSG>;    \
  template std::string ddsTypeName<MSG>()

RADARSLAM_DDS_INSTANTIATE(OccupancyGridMsg);
RADARSLAM_DDS_INSTANTIATE(PointCloud2Msg);
RADARSLAM_DDS_INSTANTIATE(OctomapMsg);
RADARSLAM_DDS_INSTANTIATE(PoseWithCovarianceStampedMsg);
RADARSLAM_DDS_INSTANTIATE(MapInfoMsg);
RADARSLAM_DDS_INSTANTIATE(RadarScanMsg);
RADARSLAM_DDS_INSTANTIATE(LocalizationStatusMsg);
RADARSLAM_DDS_INSTANTIATE(MapFileChunkMsg);
RADARSLAM_DDS_INSTANTIATE(MapTileMsg);

}  // namespace radarslam::dds
