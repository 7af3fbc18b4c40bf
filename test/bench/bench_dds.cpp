// DDS map server / pose stream measurements on loopback (issue #7), separate processes:
//   LateJoiner4000: a new participant joins while radarslam-map-server serves a 4000x4000 grid
//                   (16 MB); time from creating the participant to holding the whole grid.
//   PoseLatency:    a child process publishes PoseWithCovarianceStamped at 100 Hz with
//                   header.stamp = CLOCK_REALTIME at publish; one-way latency = receive - stamp.
//   ServerIdleCpu:  CPU time (utime+stime, /proc/PID/stat) of an idle server over 10 s.
// Run: build-X/test/bench/bench_dds   (spawns the built radarslam-map-server)
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include <radarslam/dds/domain.h>
#include <radarslam/dds/pose_publisher.h>
#include <radarslam/map/map_from_trajectory.h>
#include <radarslam/map/map_io.h>

extern char** environ;

namespace {

using namespace radarslam;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string g_self;  // path of this program (for the pose publisher child)

StampNs realtimeNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Optional XML configuration for every participant (server included): $RADARSLAM_DDS_CONFIG.
std::string configXml() {
  const char* path = std::getenv("RADARSLAM_DDS_CONFIG");
  return path ? dds::readConfigFile(path) : std::string(dds::kLoopbackConfigXml);
}
std::vector<std::string> configArgs() {
  const char* path = std::getenv("RADARSLAM_DDS_CONFIG");
  return path ? std::vector<std::string>{"--config", path} : std::vector<std::string>{};
}

unsigned domainId(unsigned i) { return 3 + (static_cast<unsigned>(::getpid()) % 20) * 10 + i; }

struct Proc {
  pid_t pid = -1;
  fs::path err;
  Proc(std::vector<std::string> args, fs::path err_path) : err(std::move(err_path)) {
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Proc() {
    if (pid > 0) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, nullptr, 0);
    }
  }
  bool waitForLog(const std::string& text, double timeout_s) const {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (Clock::now() < deadline) {
      std::ifstream in(err);
      std::stringstream ss;
      ss << in.rdbuf();
      if (ss.str().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
};

fs::path scratch() {
  const fs::path p = fs::temp_directory_path() / ("radarslam_bench_dds_" + std::to_string(::getpid()));
  fs::create_directories(p);
  return p;
}

// Keyframes whose points span [-95, 95]^2 m: at 0.05 m cells plus the 5 m margin, 4000 x 4000.
void writeMap(const fs::path& dir, double half, int keyframes, int points) {
  KeyframeMap map;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-half, half);
  for (int k = 0; k < keyframes; ++k) {
    std::vector<RadarPoint> cloud;
    for (int i = 0; i < points; ++i) {
      RadarPoint p;
      p.x = static_cast<float>(u(rng) - k);
      p.y = static_cast<float>(u(rng));
      p.power = 100.f;
      cloud.push_back(p);
    }
    for (double cx : {-half, half})
      for (double cy : {-half, half}) {
        RadarPoint p;
        p.x = static_cast<float>(cx - k);
        p.y = static_cast<float>(cy);
        cloud.push_back(p);
      }
    addKeyframe(map, 1'700'000'000'000'000'000LL + k * 250'000'000LL, mrpt::math::TPose2D(k, 0, 0), cloud);
  }
  saveMap(map, dir);
}

void LateJoiner4000(benchmark::State& state) {
  const fs::path dir = scratch();
  writeMap(dir / "big", 95.0, 3, 2000);
  const unsigned dom = domainId(0);
  std::vector<std::string> args{
      RADARSLAM_MAP_SERVER, "--map", (dir / "big").string(), "--domain", std::to_string(dom),
      "--layers",           "grid",  "--resolution",         "0.05"};
  for (const auto& a : configArgs()) args.push_back(a);
  Proc server(args, dir / "server.err");
  if (!server.waitForLog("published map", 60)) {
    state.SkipWithError("server did not start");
    return;
  }
  std::size_t bytes = 0;
  const std::string xml = configXml();
  for (auto _ : state) {
    const auto t0 = Clock::now();
    dds::Domain d(dom, xml);
    dds::Subscription<dds::OccupancyGridMsg> sub(d, dds::kMapTopic, dds::TopicQos::latched());
    const auto grid = sub.take(std::chrono::seconds(30));
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (!grid) {
      state.SkipWithError("no grid received");
      break;
    }
    bytes = grid->data.size();
    state.SetIterationTime(s);
  }
  state.counters["grid_MB"] = static_cast<double>(bytes) / 1e6;
  fs::remove_all(dir);
}
BENCHMARK(LateJoiner4000)->UseManualTime()->Iterations(10)->Unit(benchmark::kMillisecond);

// Child mode: publish `n` poses at 100 Hz on domain `dom`, after a subscriber matched.
int posePublisherChild(unsigned dom, int n) {
  dds::Domain d(dom);
  dds::PosePublisher pub(d);
  for (int i = 0; i < 500 && pub.matchedSubscriptions() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (int i = 0; i < n; ++i) {
    pub.publish(realtimeNs(), mrpt::math::TPose2D(i * 0.1, 0, 0), {0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.001});
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return 0;
}

void PoseLatency(benchmark::State& state) {
  const int n = 500;
  const unsigned dom = domainId(1);
  std::vector<double> lat_ms;
  for (auto _ : state) {
    dds::Domain d(dom);
    dds::Subscription<dds::PoseWithCovarianceStampedMsg> sub(d, dds::kPoseTopic, dds::TopicQos::stream(10));
    Proc child({g_self, "--pose-publisher", std::to_string(dom), std::to_string(n)}, scratch() / "pose.err");
    while (static_cast<int>(lat_ms.size()) < n) {
      const auto m = sub.take(std::chrono::seconds(10));
      const StampNs now = realtimeNs();
      if (!m) break;
      lat_ms.push_back(static_cast<double>(now - dds::fromTimeMsg(m->header.stamp)) * 1e-6);
    }
  }
  if (lat_ms.empty()) {
    state.SkipWithError("no poses received");
    return;
  }
  std::sort(lat_ms.begin(), lat_ms.end());
  state.counters["received"] = static_cast<double>(lat_ms.size());
  state.counters["median_ms"] = lat_ms[lat_ms.size() / 2];
  state.counters["p99_ms"] = lat_ms[lat_ms.size() * 99 / 100];
  state.counters["max_ms"] = lat_ms.back();
  fs::remove_all(scratch());
}
BENCHMARK(PoseLatency)->Iterations(1)->Unit(benchmark::kSecond);

double cpuSeconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string s((std::istreambuf_iterator<char>(in)), {});
  std::istringstream fields(s.substr(s.rfind(')') + 2));
  std::string f;
  long utime = 0, stime = 0;
  for (int i = 3; fields >> f; ++i) {  // field 14 utime, 15 stime (1-based, pid = 1)
    if (i == 14) utime = std::stol(f);
    if (i == 15) {
      stime = std::stol(f);
      break;
    }
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

void ServerIdleCpu(benchmark::State& state) {
  const fs::path dir = scratch();
  writeMap(dir / "small", 30.0, 4, 300);
  const unsigned dom = domainId(2);
  Proc server({RADARSLAM_MAP_SERVER, "--map", (dir / "small").string(), "--domain", std::to_string(dom)},
              dir / "server.err");
  if (!server.waitForLog("serving", 60)) {
    state.SkipWithError("server did not start");
    return;
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  double used = 0;
  for (auto _ : state) {
    const double c0 = cpuSeconds(server.pid);
    std::this_thread::sleep_for(std::chrono::seconds(10));
    used = cpuSeconds(server.pid) - c0;
  }
  state.counters["cpu_s_per_10s"] = used;
  state.counters["cpu_percent"] = used / 10.0 * 100.0;
  fs::remove_all(dir);
}
BENCHMARK(ServerIdleCpu)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

int main(int argc, char** argv) {
  g_self = fs::canonical("/proc/self/exe").string();
  if (argc == 4 && std::strcmp(argv[1], "--pose-publisher") == 0)
    return posePublisherChild(static_cast<unsigned>(std::stoul(argv[2])), std::stoi(argv[3]));
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
