#include "radarslam/dds/map_file_receiver.h"

#include <chrono>
#include <cstdio>

#include "radarslam/core/errors.h"
#include "radarslam/core/log.h"
#include "radarslam/dds/domain.h"
#include "radarslam/dds/map_file_assembler.h"

namespace radarslam::dds {

ReceivedMapFiles receiveMapFiles(Domain& domain, const std::filesystem::path& dir,
                                 const MapReceiveParams& params, const std::string& source) {
  using Clock = std::chrono::steady_clock;
  if (!(params.timeout_s > 0)) throw InputError(source, "the map timeout must be > 0 s");
  const auto t0 = Clock::now();
  const auto deadline =
      t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(params.timeout_s));
  Subscription<MapFileChunkMsg> sub(domain, kMapFilesTopic, TopicQos::latchedAll());
  MapFileAssembler assembler(dir, source, params.max_bytes);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    auto chunk = left.count() > 0 ? sub.take(left) : std::nullopt;
    if (!chunk) break;
    if (assembler.add(*chunk)) {
      ReceivedMapFiles r;
      r.map_name = assembler.mapName();
      r.revision = assembler.revision();
      r.files = assembler.filesComplete();
      r.chunks = assembler.chunksReceived();
      r.bytes = assembler.bytesReceived();
      r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      if (assembler.chunksIgnored() > 0)
        logger().logFmt(mrpt::system::LVL_INFO, "%s: ignored %zu chunks of older map publications",
                        source.c_str(), assembler.chunksIgnored());
      return r;
    }
  }
  char what[256];
  if (assembler.totalChunks() == 0)
    std::snprintf(what, sizeof what,
                  "no map on %s within %g s (is radarslam-map-server running on domain %u?)", kMapFilesTopic,
                  params.timeout_s, domain.id());
  else
    std::snprintf(what, sizeof what,
                  "no complete map on %s within %g s (%zu of %u chunks of '%s' revision %u)", kMapFilesTopic,
                  params.timeout_s, assembler.chunksReceived(), assembler.totalChunks(),
                  assembler.mapName().c_str(), assembler.revision());
  throw InputError(source, what);
}

}  // namespace radarslam::dds
