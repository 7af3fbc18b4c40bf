#pragma once
// A thin RAII layer over the Cyclone DDS C API (the only place that talks to it): a domain and
// participant created from an XML configuration, and typed publishers/subscriptions for the
// messages of dds/messages.h. All data is sent as XCDR1, as ROS 2 (rmw_cyclonedds) does.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "radarslam/dds/messages.h"

namespace radarslam::dds {

/// Loopback-only configuration (the content of config/dds.xml): no multicast, unicast discovery
/// to 127.0.0.1, so nothing leaves the host unless a configuration says otherwise; 60 kB fragments
/// (lo has a 64 kB MTU; a 16 MB grid reaches a late joiner ~2.5x sooner than with the defaults).
extern const char* const kLoopbackConfigXml;

/// Reads an XML configuration file; throws InputError(path, ...) if it cannot be read or does not
/// look like a Cyclone DDS configuration (<CycloneDDS ...>).
std::string readConfigFile(const std::filesystem::path& path);

/// Domain ids Cyclone accepts with the default port mapping (7400 + 250 * id < 65536).
constexpr std::uint32_t kMaxDomainId = 232;

/// One DDS domain (configured from XML text) and a participant in it. Not copyable.
class Domain {
 public:
  /// Throws InputError("DDS domain N", reason) if the domain or participant cannot be created
  /// (e.g. malformed XML, bad id, the interface does not exist).
  explicit Domain(std::uint32_t domain_id, const std::string& config_xml = kLoopbackConfigXml);
  ~Domain();
  Domain(const Domain&) = delete;
  Domain& operator=(const Domain&) = delete;

  std::int32_t participant() const { return participant_; }
  std::uint32_t id() const { return id_; }

 private:
  std::uint32_t id_;
  std::int32_t domain_ = 0;
  std::int32_t participant_ = 0;
};

/// The DDS type name of a message (ROS 2 naming, e.g. "nav_msgs::msg::dds_::OccupancyGrid_").
template <class Msg>
std::string ddsTypeName();

/// Quality of service of one topic. Latched (maps, as nav2/mrpt map servers): RELIABLE,
/// TRANSIENT_LOCAL, KEEP_LAST 1, so a subscriber that joins later still gets the last sample.
/// Transient local: a late joiner gets what the writer's history holds (KEEP_LAST depth, or all).
struct TopicQos {
  bool reliable = true;
  bool transient_local = false;
  std::int32_t depth = 1;  ///< KEEP_LAST depth
  bool keep_all = false;   ///< KEEP_ALL instead of KEEP_LAST depth
  static TopicQos latched() { return {true, true, 1}; }
  /// Latched, the last `depth` samples (e.g. every chunk of a map's files).
  static TopicQos latchedLast(std::int32_t depth) { return {true, true, depth}; }
  /// Reliable, transient local, keep all (a reader that must not lose a latched sample).
  static TopicQos latchedAll() { return {true, true, 1, true}; }
  static TopicQos stream(std::int32_t depth = 10) { return {true, false, depth}; }
  static TopicQos bestEffort(std::int32_t depth = 1) { return {false, false, depth}; }
};

/// Writer of one message type on one topic. Msg is one of the types in dds/messages.h.
template <class Msg>
class Publisher {
 public:
  Publisher(Domain& domain, const std::string& topic, const TopicQos& qos);
  ~Publisher();
  Publisher(const Publisher&) = delete;
  Publisher& operator=(const Publisher&) = delete;

  /// Sends `msg` (blocks at most the reliability max-blocking time if readers are slow).
  /// Throws std::runtime_error on a DDS error.
  void publish(const Msg& msg);
  /// Number of matched subscriptions right now.
  std::uint32_t matchedSubscriptions() const;
  /// Blocks until at least `count` subscriptions matched or the timeout passed; true if matched.
  bool waitForSubscriptions(std::uint32_t count, std::chrono::milliseconds timeout) const;
  /// Blocks until every reliable subscriber acknowledged all samples (or the timeout); true if so.
  bool waitForAcknowledgements(std::chrono::milliseconds timeout) const;

 private:
  std::int32_t topic_ = 0;
  std::int32_t writer_ = 0;
};

/// Reader of one message type on one topic.
template <class Msg>
class Subscription {
 public:
  Subscription(Domain& domain, const std::string& topic, const TopicQos& qos);
  ~Subscription();
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;

  /// Blocks (no polling) until a sample arrives or the timeout passes; returns the oldest
  /// unread sample, or nullopt on timeout.
  std::optional<Msg> take(std::chrono::milliseconds timeout);
  /// Number of matched publications right now.
  std::uint32_t matchedPublications() const;
  /// The read condition (for WaitSet::attach).
  std::int32_t readCondition() const { return condition_; }

 private:
  std::int32_t topic_ = 0;
  std::int32_t reader_ = 0;
  std::int32_t waitset_ = 0;
  std::int32_t condition_ = 0;
};

/// Blocks on several subscriptions at once (e.g. a client waiting for all map layers).
class WaitSet {
 public:
  explicit WaitSet(Domain& domain);
  ~WaitSet();
  WaitSet(const WaitSet&) = delete;
  WaitSet& operator=(const WaitSet&) = delete;
  template <class Msg>
  void attach(const Subscription<Msg>& sub) {
    attachCondition(sub.readCondition());
  }
  /// Blocks until one attached subscription has unread data or the timeout; true if data.
  bool wait(std::chrono::milliseconds timeout);

 private:
  void attachCondition(std::int32_t condition);
  std::int32_t waitset_ = 0;
};

}  // namespace radarslam::dds
