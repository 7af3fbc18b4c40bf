// fastdds_interop_client: a subscriber built on eProsima Fast DDS (ROS 2's default middleware), the
// second DDS implementation of the test suite (issue 16). It reads what radarslam's Cyclone DDS
// programs publish on loopback, with the type support fastddsgen generated from
// test/interop/idl/ros2_interop.idl (written from the ROS 2 message definitions) and readers with
// the QoS rmw_fastrtps gives a ROS 2 subscriber:
//   latched topics (map, cloud, octomap, map_info): RELIABLE, TRANSIENT_LOCAL, KEEP_LAST 1
//   pose: RELIABLE, VOLATILE, KEEP_LAST 10
// It shares no code with radarslam (SHA-256 from OpenSSL, CDR from Fast CDR).
//
// Usage: fastdds_interop_client --domain N [--topics map,cloud,octomap,map_info,map_tiles,cloud_tiles,pose]
//                               [--timeout S] [--poses N]
// One line per received sample on stdout (flushed at once), "key=value" fields:
//   received map t_ms=... stamp=SEC.NANOSEC frame=map width=... height=... resolution=...
//            origin_x=... origin_y=... data_bytes=... sha256=HEX
//   received cloud t_ms=... stamp=... frame=... width=... height=... point_step=... fields=x,y,z,...
//            data_bytes=... sha256=HEX
//   received octomap t_ms=... stamp=... frame=... id=OcTree binary=1 resolution=... data_bytes=...
//            sha256=HEX
//   received map_info t_ms=... stamp=... map_name=... revision=... keyframes=... grid_sha256=HEX
//            tile_cells=... tiles=... overview_sha256=HEX cloud_tile_count=... cloud_sha256=HEX
//   received map_tile t_ms=... stamp=... tile_x=... tile_y=... tile_count=... cells_sha256=HEX
//            width=... height=... origin_x=... origin_y=... data_bytes=... sha256=HEX   (every tile)
//   received cloud_tile t_ms=... stamp=... width=... data_bytes=... sha256=HEX     (every tile)
//   pose t_ms=... stamp=SEC.NANOSEC frame=map x=... y=... z=... qx=... qy=... qz=... qw=... cov=c0,..,c35
// plus "matched TOPIC t_ms=..." when a writer matched a reader (t_ms: since the participant was
// created). Latched topics count once (their first sample), except the tile topics: every tile of
// the publication (map_tiles: the tile_count every tile carries; cloud_tiles: MapInfo's
// cloud_tile_count, so map_info must be subscribed too). The client exits
//   0 once every requested topic was received (pose: --poses N samples; without --poses it keeps
//     receiving poses until SIGINT/SIGTERM or the timeout, and then needs at least one),
//   2 when the timeout expired (or a signal came) before that, 1 on bad arguments or a DDS error.
#include <openssl/evp.h>
#include <signal.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/core/condition/StatusCondition.hpp>
#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "ros2_interop.h"
#include "ros2_interopPubSubTypes.h"

namespace {

namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

using Clock = std::chrono::steady_clock;
Clock::time_point g_t0;
long msSinceStart() {
  return static_cast<long>(
      std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - g_t0).count());
}

std::string sha256Hex(const void* data, std::size_t n) {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (EVP_Digest(data, n, md, &len, EVP_sha256(), nullptr) != 1) return "error";
  static const char* hex = "0123456789abcdef";
  std::string s;
  for (unsigned i = 0; i < len; ++i) {
    s += hex[md[i] >> 4];
    s += hex[md[i] & 15];
  }
  return s;
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) {
    if (!s.empty()) s += ',';
    s += i;
  }
  return s;
}

/// One output line: "KIND t_ms=... key=value ...", written and flushed at once by emit().
class Line {
 public:
  explicit Line(const char* kind) : text_(kind) { kv("t_ms", std::to_string(msSinceStart())); }
  Line& kv(const char* key, const std::string& value) {
    text_ += ' ';
    text_ += key;
    text_ += '=';
    text_ += value;
    return *this;
  }
  template <class Header>
  Line& header(const Header& h) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%d.%09u", h.stamp().sec(), h.stamp().nanosec());
    return kv("stamp", buf).kv("frame", h.frame_id());
  }
  template <class Bytes>
  Line& payload(const Bytes& data) {
    return kv("data_bytes", std::to_string(data.size())).kv("sha256", sha256Hex(data.data(), data.size()));
  }
  void emit() {
    text_ += '\n';
    std::fputs(text_.c_str(), stdout);
    std::fflush(stdout);
  }

 private:
  std::string text_;
};

// The participant that finds radarslam's loopback-only Cyclone participants (config/dds.xml): UDPv4
// on 127.0.0.1 only, no multicast, no shared memory, SPDP by unicast to the well-known metatraffic
// ports of participant indices 0..9 (RTPS 9.6.1.1: 7400 + 250 domain + 10 + 2 index).
fdds::DomainParticipantQos participantQos(unsigned domain) {
  fdds::DomainParticipantQos q;
  q.name("radarslam_fastdds_interop_client");
  q.transport().use_builtin_transports = false;  // no SHM, no default UDP on every interface
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.push_back("127.0.0.1");
  q.transport().user_transports.push_back(udp);

  auto& wire = q.wire_protocol();
  rtps::Locator_t local;
  local.kind = LOCATOR_KIND_UDPv4;
  rtps::IPLocator::setIPv4(local, 127, 0, 0, 1);
  local.port = 0;  // 0: Fast DDS assigns the well-known port of this participant
  wire.builtin.metatrafficUnicastLocatorList.push_back(local);
  wire.builtin.metatrafficMulticastLocatorList.clear();
  wire.default_unicast_locator_list.push_back(local);
  wire.default_multicast_locator_list.clear();
  wire.builtin.avoid_builtin_multicast = true;
  for (unsigned i = 0; i < 10; ++i) {
    rtps::Locator_t peer;
    peer.kind = LOCATOR_KIND_UDPv4;
    rtps::IPLocator::setIPv4(peer, 127, 0, 0, 1);
    peer.port = 7400 + 250 * domain + 10 + 2 * i;
    wire.builtin.initialPeersList.push_back(peer);
  }
  return q;
}

fdds::DataReaderQos readerQos(bool latched, bool keep_all = false) {
  fdds::DataReaderQos q = fdds::DATAREADER_QOS_DEFAULT;
  q.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  q.durability().kind = latched ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS : fdds::VOLATILE_DURABILITY_QOS;
  q.history().kind = keep_all ? fdds::KEEP_ALL_HISTORY_QOS : fdds::KEEP_LAST_HISTORY_QOS;
  q.history().depth = latched ? 1 : 10;
  // Large samples (a 16 MB grid): grow the payload buffers on demand, as rmw_fastrtps does.
  q.endpoint().history_memory_policy = rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  q.data_sharing().off();
  return q;
}

// One subscribed topic: reader plus what it takes to print a sample.
struct Sub {
  std::string name;  // map, cloud, ...
  bool latched = true;
  fdds::DataReader* reader = nullptr;
  std::size_t received = 0;
  bool matched = false;
  bool every = false;                                 // a tile topic: every sample counts
  const std::size_t* expected = nullptr;              // ... and this many make it complete (0: not known yet)
  std::function<bool(fdds::DataReader*, bool)> take;  // takes one sample, prints it if asked; false if none
};

template <class Msg>
std::function<bool(fdds::DataReader*, bool)> taker(std::function<void(const Msg&)> print) {
  return [print](fdds::DataReader* r, bool print_it) {
    Msg m;
    fdds::SampleInfo info;
    while (r->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        if (print_it) print(m);
        return true;
      }
    }
    return false;
  };
}

int usage(const std::string& why) {
  std::fprintf(stderr,
               "fastdds_interop_client: %s\nusage: fastdds_interop_client --domain N "
               "[--topics map,cloud,octomap,map_info,map_tiles,cloud_tiles,pose] [--timeout S] [--poses N]\n",
               why.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  long domain = -1;
  double timeout_s = 30;
  long want_poses = 0;
  std::string topics = "map,cloud,octomap,map_info";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return usage("missing value after " + a);
    const std::string v = argv[++i];
    char* end = nullptr;
    if (a == "--domain") {
      domain = std::strtol(v.c_str(), &end, 10);
      if (*end || domain < 0 || domain > 232) return usage("bad --domain " + v);
    } else if (a == "--timeout") {
      timeout_s = std::strtod(v.c_str(), &end);
      if (*end || !(timeout_s > 0)) return usage("bad --timeout " + v);
    } else if (a == "--poses") {
      want_poses = std::strtol(v.c_str(), &end, 10);
      if (*end || want_poses < 0) return usage("bad --poses " + v);
    } else if (a == "--topics") {
      topics = v;
    } else {
      return usage("unknown option " + a);
    }
  }
  if (domain < 0) return usage("--domain is required");
  ::signal(SIGINT, onSignal);
  ::signal(SIGTERM, onSignal);

  g_t0 = Clock::now();
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipant* participant = factory->create_participant(
      static_cast<fdds::DomainId_t>(domain), participantQos(static_cast<unsigned>(domain)));
  if (!participant) {
    std::fprintf(stderr, "fastdds_interop_client: cannot create the participant on domain %ld\n", domain);
    return 1;
  }
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);

  std::vector<Sub> subs;
  std::size_t map_tiles_expected = 0, cloud_tiles_expected = 0;  // from the samples themselves
  auto add = [&](const std::string& name, const char* topic, fdds::TypeSupport type, bool latched,
                 std::function<bool(fdds::DataReader*, bool)> take,
                 const std::size_t* every = nullptr) -> bool {
    type.register_type(participant);
    fdds::Topic* t = participant->create_topic(topic, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    fdds::DataReader* r =
        t ? subscriber->create_datareader(t, readerQos(latched, every != nullptr)) : nullptr;
    if (!r) {
      std::fprintf(stderr, "fastdds_interop_client: cannot create a reader on %s\n", topic);
      return false;
    }
    subs.push_back(Sub{name, latched, r, 0, false, every != nullptr, every, std::move(take)});
    return true;
  };

  std::stringstream list(topics);
  bool ok = true;
  for (std::string name; std::getline(list, name, ',');) {
    if (name == "map") {
      using Msg = nav_msgs::msg::dds_::OccupancyGrid_;
      ok &= add(name, "rt/map", fdds::TypeSupport(new nav_msgs::msg::dds_::OccupancyGrid_PubSubType()), true,
                taker<Msg>([](const Msg& m) {
                  const auto& info = m.info();
                  Line("received map")
                      .header(m.header())
                      .kv("width", std::to_string(info.width()))
                      .kv("height", std::to_string(info.height()))
                      .kv("resolution", num(info.resolution()))
                      .kv("origin_x", num(info.origin().position().x()))
                      .kv("origin_y", num(info.origin().position().y()))
                      .payload(m.data())
                      .emit();
                }));
    } else if (name == "cloud") {
      using Msg = sensor_msgs::msg::dds_::PointCloud2_;
      ok &= add(name, "rt/radarslam/cloud_map",
                fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType()), true,
                taker<Msg>([](const Msg& m) {
                  std::vector<std::string> fields;
                  for (const auto& f : m.fields()) fields.push_back(f.name());
                  Line("received cloud")
                      .header(m.header())
                      .kv("width", std::to_string(m.width()))
                      .kv("height", std::to_string(m.height()))
                      .kv("point_step", std::to_string(m.point_step()))
                      .kv("fields", join(fields))
                      .payload(m.data())
                      .emit();
                }));
    } else if (name == "octomap") {
      using Msg = octomap_msgs::msg::dds_::Octomap_;
      ok &= add(name, "rt/radarslam/octomap",
                fdds::TypeSupport(new octomap_msgs::msg::dds_::Octomap_PubSubType()), true,
                taker<Msg>([](const Msg& m) {
                  Line("received octomap")
                      .header(m.header())
                      .kv("id", m.id())
                      .kv("binary", m.binary() ? "1" : "0")
                      .kv("resolution", num(m.resolution()))
                      .payload(m.data())
                      .emit();
                }));
    } else if (name == "map_info") {
      using Msg = radarslam::msg::dds_::MapInfo_;
      ok &= add(name, "rt/radarslam/map_info",
                fdds::TypeSupport(new radarslam::msg::dds_::MapInfo_PubSubType()), true,
                taker<Msg>([&cloud_tiles_expected](const Msg& m) {
                  cloud_tiles_expected = m.cloud_tile_count();
                  Line("received map_info")
                      .header(m.header())
                      .kv("map_name", m.map_name())
                      .kv("revision", std::to_string(m.revision()))
                      .kv("keyframes", std::to_string(m.keyframes()))
                      .kv("grid_sha256", m.grid_sha256())
                      .kv("tile_cells", std::to_string(m.tile_cells()))
                      .kv("tiles", std::to_string(m.tile_indices().size()))
                      .kv("overview_sha256", m.overview_sha256().empty() ? "-" : m.overview_sha256())
                      .kv("cloud_tile_count", std::to_string(m.cloud_tile_count()))
                      .kv("cloud_sha256", m.cloud_sha256().empty() ? "-" : m.cloud_sha256())
                      .emit();
                }));
    } else if (name == "map_tiles") {
      using Msg = radarslam::msg::dds_::MapTile_;
      ok &= add(name, "rt/radarslam/map_tiles",
                fdds::TypeSupport(new radarslam::msg::dds_::MapTile_PubSubType()), true,
                taker<Msg>([&map_tiles_expected](const Msg& m) {
                  map_tiles_expected = m.tile_count();
                  const auto& info = m.grid().info();
                  Line("received map_tile")
                      .header(m.header())
                      .kv("tile_x", std::to_string(m.tile_x()))
                      .kv("tile_y", std::to_string(m.tile_y()))
                      .kv("tile_count", std::to_string(m.tile_count()))
                      .kv("cells_sha256", m.cells_sha256())
                      .kv("width", std::to_string(info.width()))
                      .kv("height", std::to_string(info.height()))
                      .kv("origin_x", num(info.origin().position().x()))
                      .kv("origin_y", num(info.origin().position().y()))
                      .payload(m.grid().data())
                      .emit();
                }),
                &map_tiles_expected);
    } else if (name == "cloud_tiles") {
      using Msg = sensor_msgs::msg::dds_::PointCloud2_;
      ok &= add(name, "rt/radarslam/cloud_map_tiles",
                fdds::TypeSupport(new sensor_msgs::msg::dds_::PointCloud2_PubSubType()), true,
                taker<Msg>([](const Msg& m) {
                  Line("received cloud_tile")
                      .header(m.header())
                      .kv("width", std::to_string(m.width()))
                      .payload(m.data())
                      .emit();
                }),
                &cloud_tiles_expected);
    } else if (name == "pose") {
      using Msg = geometry_msgs::msg::dds_::PoseWithCovarianceStamped_;
      ok &= add(name, "rt/radarslam/pose",
                fdds::TypeSupport(new geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType()),
                false, taker<Msg>([](const Msg& m) {
                  const auto& p = m.pose().pose();
                  std::vector<std::string> cov;
                  for (double c : m.pose().covariance()) cov.push_back(num(c));
                  Line("pose")
                      .header(m.header())
                      .kv("x", num(p.position().x()))
                      .kv("y", num(p.position().y()))
                      .kv("z", num(p.position().z()))
                      .kv("qx", num(p.orientation().x()))
                      .kv("qy", num(p.orientation().y()))
                      .kv("qz", num(p.orientation().z()))
                      .kv("qw", num(p.orientation().w()))
                      .kv("cov", join(cov))
                      .emit();
                }));
    } else {
      ok = false;
      std::fprintf(stderr, "fastdds_interop_client: unknown topic '%s'\n", name.c_str());
    }
  }
  int rc = 1;
  if (ok && !subs.empty()) {
    fdds::WaitSet waitset;
    for (auto& s : subs) {
      fdds::StatusMask mask = fdds::StatusMask::data_available();
      mask << fdds::StatusMask::subscription_matched();
      s.reader->get_statuscondition().set_enabled_statuses(mask);
      waitset.attach_condition(s.reader->get_statuscondition());
    }
    const auto deadline = g_t0 + std::chrono::duration<double>(timeout_s);
    auto complete = [&](bool stopping) {
      for (const auto& s : subs) {
        if (s.every && (*s.expected == 0 || s.received < *s.expected)) return false;
        if (s.latched && s.received == 0) return false;
        if (!s.latched && (want_poses > 0 ? s.received < static_cast<std::size_t>(want_poses)
                                          : (!stopping || s.received == 0)))
          return false;
      }
      return true;
    };
    for (;;) {
      fdds::ConditionSeq active;
      waitset.wait(active, eprosima::fastrtps::Duration_t(0, 100'000'000));
      for (auto& s : subs) {
        // Reading the statuses resets them: a writer that leaves (localize exits) or a second
        // latched sample (a reload) must not keep the wait set triggered.
        fdds::SubscriptionMatchedStatus st;
        if (s.reader->get_subscription_matched_status(st) == ReturnCode_t::RETCODE_OK && !s.matched &&
            st.current_count > 0) {
          s.matched = true;
          Line((std::string("matched ") + s.name).c_str()).emit();
        }
        // A latched topic is printed and counted once (its first sample); later ones are dropped.
        // A tile topic: every sample.
        for (bool first = s.every || !s.latched || s.received == 0; s.take(s.reader, first);
             first = s.every || !s.latched)
          if (first) ++s.received;
      }
      if (complete(false)) {
        rc = 0;
        break;
      }
      if (g_stop || Clock::now() > deadline) {
        rc = complete(true) ? 0 : 2;
        break;
      }
    }
    Line summary("summary");
    for (const auto& s : subs) summary.kv(s.name.c_str(), std::to_string(s.received));
    summary.kv("exit", std::to_string(rc)).emit();
    if (rc == 2)
      std::fprintf(stderr, "fastdds_interop_client: timed out or stopped before every topic arrived\n");
  }
  participant->delete_contained_entities();
  factory->delete_participant(participant);
  return rc;
}
