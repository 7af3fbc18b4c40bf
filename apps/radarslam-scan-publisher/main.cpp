// radarslam-scan-publisher: replays a dataset (any format io/dataset.h reads) as
// radarslam/RadarScan messages on rt/radarslam/radar_scan, a DDS scan source for testing what a
// live radar driver would feed the localiser (dds/scan_subscriber.h).
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <thread>

#include <radarslam/core/errors.h>
#include <radarslam/core/log.h>
#include <radarslam/dds/domain.h>
#include <radarslam/dds/scan_messages.h>
#include <radarslam/io/dataset.h>
#include <radarslam/obs/registration.h>

#include "cli_common.h"

namespace {

using namespace radarslam;
using mrpt::system::LVL_INFO;

int run(int argc, char** argv) {
  cli::CommandLine cmd(
      "scan-publisher",
      "Replays a dataset's radar scans as radarslam/RadarScan DDS messages (RELIABLE, VOLATILE).");
  auto& tc = cmd.tclap();
  TCLAP::UnlabeledValueArg<std::string> dataset("dataset", "Dataset directory (or rawlog)", true, "", "DIR",
                                                tc);
  TCLAP::ValueArg<std::string> config(
      "", "config", "Cyclone DDS XML configuration (default: built-in loopback)", false, "", "FILE", tc);
  TCLAP::ValueArg<unsigned> domain("", "domain", "DDS domain id (ROS_DOMAIN_ID), 0..232", false, 0, "N", tc);
  TCLAP::ValueArg<std::string> topic("", "topic", "DDS topic", false, dds::kRadarScanTopic, "NAME", tc);
  TCLAP::ValueArg<double> rate("", "rate",
                               "Replay speed: 1 = real time from the scan stamps, 0 = as fast as "
                               "reliable delivery allows",
                               false, 1.0, "X", tc);
  TCLAP::ValueArg<std::size_t> count("", "count", "Publish at most this many scans (0 = all)", false, 0, "N",
                                     tc);
  TCLAP::ValueArg<unsigned> subscribers("", "wait-subscribers",
                                        "Wait for this many subscribers before sending", false, 0, "N", tc);
  TCLAP::ValueArg<double> wait_timeout("", "wait-timeout", "Seconds to wait for --wait-subscribers", false,
                                       30.0, "S", tc);
  TCLAP::ValueArg<std::string> frame("", "frame-id", "header.frame_id of the scans", false, "radar", "NAME",
                                     tc);
  cmd.parse(argc, argv);
  if (!(rate.getValue() >= 0)) throw InputError("--rate", "must be >= 0");

  registerRadarslamClasses();
  const auto reader = openDataset(dataset.getValue());
  const std::string xml = config.isSet() ? dds::readConfigFile(config.getValue()) : dds::kLoopbackConfigXml;
  dds::Domain dom(domain.getValue(), xml);
  dds::Publisher<dds::RadarScanMsg> pub(dom, topic.getValue(), dds::TopicQos::stream(16));
  if (subscribers.getValue() > 0 &&
      !pub.waitForSubscriptions(subscribers.getValue(),
                                std::chrono::milliseconds(static_cast<long>(wait_timeout.getValue() * 1000))))
    throw std::runtime_error("no " + std::to_string(subscribers.getValue()) + " subscriber(s) on " +
                             topic.getValue() + " within " + std::to_string(wait_timeout.getValue()) + " s");

  ScanIterator it(*reader, /*skip_bad_scans=*/true);
  const std::size_t n = count.getValue() ? std::min(count.getValue(), it.total()) : it.total();
  const auto t0 = std::chrono::steady_clock::now();
  StampNs first_stamp = 0;
  std::size_t sent = 0;
  while (sent < n) {
    const auto scan = it.next();
    if (!scan) break;
    if (sent == 0) first_stamp = scan->refStampNs();
    if (rate.getValue() > 0) {  // pace by the dataset's own clock
      const double due_s = toSeconds(scan->refStampNs() - first_stamp) / rate.getValue();
      std::this_thread::sleep_until(t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(due_s)));
    }
    pub.publish(dds::scanMessage(*scan, frame.getValue()));
    ++sent;
    logger().logFmt(mrpt::system::LVL_DEBUG, "sent scan %zu/%zu", sent, n);
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  logger().logFmt(LVL_INFO, "published %zu scans in %.2f s (%.1f scans/s)", sent, secs,
                  secs > 0 ? sent / secs : 0.0);
  // Reliable delivery of the last scans: keep the writer alive until they are acknowledged.
  pub.waitForAcknowledgements(std::chrono::seconds(10));
  std::printf("published %zu scans\n", sent);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const radarslam::InputError& e) {
    std::cerr << "radarslam-scan-publisher: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "radarslam-scan-publisher: error: " << radarslam::describeException(e) << "\n";
    return 1;
  }
}
