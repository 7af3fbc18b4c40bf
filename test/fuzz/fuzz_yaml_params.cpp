// Fuzz target: YAML configs. YamlParams::fromText (MRPT's YAML parser) then every module's
// loadParams: the whole odometry config (OdometryParams: `cartesian:` + `odometry:`, as
// `radarslam odometry --config` reads it), `peak_cloud:`, the loop closure (`m2dp:`,
// `loop_detector:`, `loop_verifier:`) and back end (`pose_graph:`), every get() type with and
// without a Range, unknown keys. Deep nesting (seeds/yaml_params/deep_nesting.yaml) must be an
// InputError from the pre-scan, never a stack overflow in the parser.
#include "fuzz_common.h"
#include "radarslam/backend/pose_graph.h"
#include "radarslam/core/yaml_params.h"
#include "radarslam/frontend/odometry_params.h"
#include "radarslam/loop/loop_detector.h"
#include "radarslam/loop/loop_verifier.h"
#include "radarslam/loop/m2dp.h"
#include "radarslam/radar/cartesian.h"
#include "radarslam/radar/peak_cloud.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radarslam::fuzz::quietLogger();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  radarslam::fuzz::expectOnlyInputError([&] {
    const auto yaml = radarslam::YamlParams::fromText(text, "fuzz.yaml");
    radarslam::OdometryParams odometry;
    radarslam::loadParams(yaml, odometry);
    radarslam::PeakCloudParams peaks;
    radarslam::loadParams(yaml.section("peak_cloud"), peaks);
    radarslam::M2DPParams m2dp;
    radarslam::loadParams(yaml.section("m2dp"), m2dp);
    radarslam::LoopDetectorParams detector;
    radarslam::loadParams(yaml.section("loop_detector"), detector);
    radarslam::LoopVerifierParams verifier;
    radarslam::loadParams(yaml.section("loop_verifier"), verifier);
    radarslam::PoseGraphParams graph;
    radarslam::loadParams(yaml.section("pose_graph"), graph);
    const auto other = yaml.section("other");
    double d = 0;
    float f = 0;
    int i = 0;
    unsigned u = 0;
    bool b = false;
    std::string s;
    std::vector<double> v;
    other.get("d", d);
    other.get("f", f);
    other.get("i", i);
    other.get("u", u);
    other.get("b", b);
    other.get("s", s);
    other.get("v", v);
    other.get("rd", d, radarslam::Range::closed(-1, 1));
    other.get("rf", f, radarslam::Range::above(0, 1));
    other.get("ri", i, radarslam::Range::closed(0, 100));
    other.get("ru", u, radarslam::Range::closed(0, 100));
    long l = 0;
    std::size_t z = 0;
    other.get("rl", l, radarslam::Range::closed(0, 1e6));
    other.get("rz", z, radarslam::Range::closed(0, 1e6));
    other.get("rv", v, radarslam::Range::closed(0, 10), 8);
    yaml.rejectUnknownKeys();
  });
  return 0;
}
