// Keyframe descriptor database and candidate retrieval (paper Sec. III-C); see loop_detector.h.
#include "radarslam/loop/loop_detector.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nanoflann.hpp>
#include <stdexcept>

#include "radarslam/core/errors.h"
#include "radarslam/core/yaml_params.h"

namespace radarslam {

void loadParams(const YamlParams& yaml, LoopDetectorParams& params) {
  yaml.get("max_descriptor_distance", params.max_descriptor_distance, Range::above(0, 100));
  int k = static_cast<int>(params.max_candidates), recent = static_cast<int>(params.exclude_recent);
  yaml.get("max_candidates", k, Range::closed(1, 1000));
  yaml.get("exclude_recent", recent, Range::closed(0, 1000000.0));
  yaml.get("exclude_recent_distance_m", params.exclude_recent_distance_m, Range::closed(0, 1000000.0));
  params.max_candidates = static_cast<std::size_t>(k);
  params.exclude_recent = static_cast<std::size_t>(recent);
}

namespace {
/// nanoflann dataset adaptor over a flat row-major array of descriptors.
struct DescriptorStore {
  std::size_t dim = 0;
  std::vector<float> data;
  std::size_t kdtree_get_point_count() const { return dim == 0 ? 0 : data.size() / dim; }
  float kdtree_get_pt(std::size_t idx, std::size_t d) const { return data[idx * dim + d]; }
  template <class BBOX>
  bool kdtree_get_bbox(BBOX&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<float, DescriptorStore>,
                                                        DescriptorStore, -1, std::uint32_t>;
}  // namespace

struct LoopDetector::Impl {
  DescriptorStore store;
  std::vector<double> travelled;
  std::vector<bool> valid;
  std::vector<std::size_t> keyframe_of_row;
  std::unique_ptr<Tree> tree;
};

LoopDetector::LoopDetector(const LoopDetectorParams& params)
    : params_(params), impl_(std::make_unique<Impl>()) {}
LoopDetector::~LoopDetector() = default;

std::size_t LoopDetector::size() const { return impl_->travelled.size(); }

std::size_t LoopDetector::add(const M2DPDescriptor& descriptor, double travelled_m) {
  Impl& m = *impl_;
  const std::size_t id = m.travelled.size();
  m.travelled.push_back(travelled_m);
  m.valid.push_back(descriptor.size() > 0);
  if (descriptor.size() == 0) return id;
  if (m.store.dim == 0) {
    m.store.dim = static_cast<std::size_t>(descriptor.size());
    m.tree = std::make_unique<Tree>(static_cast<int>(m.store.dim), m.store,
                                    nanoflann::KDTreeSingleIndexAdaptorParams(10));
  }
  if (static_cast<std::size_t>(descriptor.size()) != m.store.dim)
    throw std::invalid_argument("LoopDetector::add: descriptor length differs from the database's");
  const auto row = static_cast<std::uint32_t>(m.keyframe_of_row.size());
  m.store.data.insert(m.store.data.end(), descriptor.data(), descriptor.data() + descriptor.size());
  m.keyframe_of_row.push_back(id);
  m.tree->addPoints(row, row);
  return id;
}

std::vector<LoopCandidate> LoopDetector::query(std::span<const M2DPDescriptor> descriptors,
                                               double travelled_m) const {
  const Impl& m = *impl_;
  std::map<std::size_t, float> best;  // keyframe -> smallest distance
  if (!m.tree) return {};
  const std::size_t n = m.travelled.size();
  const float r2 = params_.max_descriptor_distance * params_.max_descriptor_distance;
  std::vector<std::pair<std::uint32_t, float>> hits;
  for (const auto& d : descriptors) {
    if (static_cast<std::size_t>(d.size()) != m.store.dim) continue;
    hits.clear();
    nanoflann::RadiusResultSet<float, std::uint32_t> result(r2, hits);
    m.tree->findNeighbors(result, d.data(), nanoflann::SearchParams());
    for (const auto& [row, dist2] : hits) {
      const std::size_t kf = m.keyframe_of_row[row];
      if (isRecent(params_, kf, m.travelled[kf], n, travelled_m)) continue;
      const float dist = std::sqrt(dist2);
      auto [it, inserted] = best.emplace(kf, dist);
      if (!inserted) it->second = std::min(it->second, dist);
    }
  }
  std::vector<LoopCandidate> out;
  out.reserve(best.size());
  for (const auto& [kf, dist] : best) out.push_back({kf, dist});
  std::sort(out.begin(), out.end(), [](const LoopCandidate& a, const LoopCandidate& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.keyframe < b.keyframe;
  });
  if (out.size() > params_.max_candidates) out.resize(params_.max_candidates);
  return out;
}

}  // namespace radarslam
