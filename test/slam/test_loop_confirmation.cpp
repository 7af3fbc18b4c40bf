// slam/loop_confirmation.h: ambiguous loops enter the graph once the next keyframes' best
// alignments agree with them. A second pass along a street, its odometry 15 m and 4 deg off the
// first pass's: the right loops of consecutive queries confirm each other; best alignments that
// slide along the street at every keyframe, two loops of one query, a chain with a gap, or two
// placements that are each consistent (look-alike blocks) are not confirmed.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "loop_confirmation.h"

namespace radarslam::slam_detail {
namespace {

constexpr std::uint64_t kQuery0 = 100;  // second-pass keyframe ids: kQuery0 + k

/// First pass: keyframes 0..59 every 2 m along x. Second pass: the same places driven the other
/// way, 3.5 m to the side, as its odometry has them (15 m and 4 deg off the truth).
struct Street {
  std::vector<TPose2D> poses = std::vector<TPose2D>(kQuery0 + 60);
  std::vector<TPose2D> truth = std::vector<TPose2D>(kQuery0 + 60);
  Street() {
    const TPose2D drift(-6.0, 13.7, 4.0 * M_PI / 180);  // odometry frame of the second pass vs truth
    for (int k = 0; k < 60; ++k) {
      poses[k] = truth[k] = TPose2D(2.0 * k, 0, 0);
      truth[kQuery0 + k] = TPose2D(118.0 - 2.0 * k, 3.5, M_PI);
      poses[kQuery0 + k] = compose(drift, truth[kQuery0 + k]);
    }
  }
  std::function<TPose2D(std::uint64_t)> pose() const {
    return [this](std::uint64_t k) { return poses.at(k); };
  }
  /// Second-pass keyframe k's loop to the first-pass keyframe at its place, its relative pose
  /// moved by `slide_m` along the street and perturbed by noise of the loop sigmas.
  PendingLoop loop(int k, double slide_m, std::mt19937& rng) const {
    std::normal_distribution<double> xy(0, 0.1), phi(0, 0.5 * M_PI / 180);
    PendingLoop l;
    l.query = kQuery0 + static_cast<std::uint64_t>(k);
    l.match = static_cast<std::uint64_t>(59 - k);
    const TPose2D rel = between(truth[l.match], truth[l.query]);
    l.relative = TPose2D(rel.x + slide_m + xy(rng), rel.y + xy(rng), rel.phi + phi(rng));
    l.information = Eigen::Vector3d(1 / 0.04, 1 / 0.04, 1 / std::pow(M_PI / 180, 2)).asDiagonal();
    l.record = static_cast<std::size_t>(k) * 10 + (slide_m != 0);
    return l;
  }
};

TEST(LoopConfirmation, RightLoopsOfConsecutiveKeyframesConfirmEachOther) {
  const Street street;
  std::mt19937 rng(1);
  LoopConfirmation confirmation(3, 3, 16.27);
  EXPECT_TRUE(confirmation.add(street.loop(10, 0, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(11, 0, rng), street.pose()).empty());
  const auto confirmed = confirmation.add(street.loop(13, 0, rng), street.pose());  // a gap of 2
  ASSERT_EQ(confirmed.size(), 3u);
  EXPECT_EQ(confirmed[0].query, kQuery0 + 10);
  EXPECT_EQ(confirmed[2].query, kQuery0 + 13);
  // A later agreeing loop enters at once, alone.
  const auto next = confirmation.add(street.loop(14, 0, rng), street.pose());
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].query, kQuery0 + 14);
}

TEST(LoopConfirmation, BestAlignmentsThatSlideAlongTheStreetAreNeverConfirmed) {
  const Street street;
  std::mt19937 rng(2);
  LoopConfirmation confirmation(3, 3, 16.27);
  // A featureless wall: the best alignment lands 5-17 m along, elsewhere at every keyframe (any two
  // within the gap at least 3 m apart: 12 sigma of the loops' 0.2 m).
  for (int k = 0; k < 50; ++k) {
    const double slide_m = 5 + 3 * (k % 5);
    EXPECT_TRUE(confirmation.add(street.loop(k, slide_m, rng), street.pose()).empty()) << "keyframe " << k;
  }
}

TEST(LoopConfirmation, RightLoopsAmongWrongOnesAreConfirmedAndTheWrongOnesNot) {
  const Street street;
  std::mt19937 rng(3);
  LoopConfirmation confirmation(3, 3, 16.27);
  std::size_t right = 0;
  for (int k = 0; k < 30; ++k) {
    for (const auto& c : confirmation.add(street.loop(k, 5 + 3 * (k % 5), rng), street.pose()))
      ADD_FAILURE() << "wrong loop of keyframe " << c.query << " confirmed";
    if (k % 2 == 0) right += confirmation.add(street.loop(k, 0, rng), street.pose()).size();
  }
  EXPECT_EQ(right, 15u);  // every right loop, from the third on with the two before it
}

TEST(LoopConfirmation, TwoPlacementsEachConsistentHoldEachOtherBack) {
  // A street of look-alike blocks: at every keyframe the right place and one a block further on
  // (105 m) both fit, each consistently from keyframe to keyframe.
  const Street street;
  std::mt19937 rng(7);
  LoopConfirmation confirmation(3, 3, 16.27);
  for (int k = 0; k < 12; ++k) {
    EXPECT_TRUE(confirmation.add(street.loop(k, 105, rng), street.pose()).empty()) << k;
    EXPECT_TRUE(confirmation.add(street.loop(k, 0, rng), street.pose()).empty()) << k;
  }
  EXPECT_GT(confirmation.rivalled(), 0u);
  // The look-alike block ends: once its chain has left the window (3 x 3 keyframes) the right one
  // is confirmed, with the loops it held back, and nothing of the other.
  std::size_t first = 0, confirmed = 0;
  for (int k = 12; k < 30 && confirmed == 0; ++k) {
    const auto c = confirmation.add(street.loop(k, 0, rng), street.pose());
    for (const auto& l : c) EXPECT_EQ(l.record % 10, 0u) << "a loop of the other block";
    if (!c.empty()) first = static_cast<std::size_t>(k), confirmed = c.size();
  }
  EXPECT_GE(first, 20u);
  EXPECT_LE(first, 22u);
  EXPECT_GE(confirmed, 3u);
}

TEST(LoopConfirmation, APlacementThePriorExcludesIsNeverConfirmedButStillARival) {
  const Street street;
  std::mt19937 rng(8);
  LoopConfirmation beyond(3, 3, 16.27);
  for (int k = 0; k < 8; ++k) {
    PendingLoop l = street.loop(k, 0, rng);
    l.eligible = false;
    EXPECT_TRUE(beyond.add(l, street.pose()).empty()) << k;
  }
  LoopConfirmation rivalled(3, 3, 16.27);
  for (int k = 0; k < 8; ++k) {
    PendingLoop far = street.loop(k, 105, rng);
    far.eligible = false;
    EXPECT_TRUE(rivalled.add(far, street.pose()).empty()) << k;
    EXPECT_TRUE(rivalled.add(street.loop(k, 0, rng), street.pose()).empty()) << k;
  }
}

TEST(LoopConfirmation, AUniqueLoopConfirmsWhatAgreesWithItAndWithdrawsWhatContradictsIt) {
  const Street street;
  std::mt19937 rng(9);
  // A look-alike block 105 m on, consistent over three keyframes: confirmed (nothing else known).
  LoopConfirmation confirmation(3, 3, 16.27);
  EXPECT_TRUE(confirmation.add(street.loop(10, 105, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(11, 105, rng), street.pose()).empty());
  EXPECT_EQ(confirmation.add(street.loop(12, 105, rng), street.pose()).size(), 3u);
  // Then the verifier finds the right place unique: the three are withdrawn...
  const auto withdrawn = confirmation.addUnique(street.loop(13, 0, rng), street.pose());
  EXPECT_EQ(withdrawn.size(), 3u);
  for (const std::size_t r : withdrawn) EXPECT_EQ(r % 10, 1u) << "a right loop withdrawn";
  // ... an ambiguous loop that agrees with the unique one enters at once, one that does not waits.
  EXPECT_EQ(confirmation.add(street.loop(14, 0, rng), street.pose()).size(), 1u);
  EXPECT_TRUE(confirmation.add(street.loop(14, 105, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(15, 105, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(16, 105, rng), street.pose()).empty());
}

TEST(LoopConfirmation, AGapLongerThanTheMaximumBreaksTheChain) {
  const Street street;
  std::mt19937 rng(4);
  LoopConfirmation confirmation(3, 3, 16.27);
  EXPECT_TRUE(confirmation.add(street.loop(10, 0, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(11, 0, rng), street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(15, 0, rng), street.pose()).empty());  // 4 > 3
  EXPECT_EQ(confirmation.add(street.loop(16, 0, rng), street.pose()).size(), 0u);
  EXPECT_EQ(confirmation.add(street.loop(17, 0, rng), street.pose()).size(), 3u);
}

TEST(LoopConfirmation, TwoLoopsOfOneQueryAreNotTwoKeyframes) {
  const Street street;
  std::mt19937 rng(5);
  LoopConfirmation confirmation(3, 3, 16.27);
  PendingLoop a = street.loop(20, 0, rng), b = street.loop(20, 0, rng);
  b.record = 999;
  EXPECT_TRUE(confirmation.add(a, street.pose()).empty());
  EXPECT_TRUE(confirmation.add(b, street.pose()).empty());
  EXPECT_TRUE(confirmation.add(street.loop(21, 0, rng), street.pose()).empty());
  EXPECT_EQ(confirmation.add(street.loop(22, 0, rng), street.pose()).size(), 3u);
}

/// The chi^2 of an error (lateral y, heading phi) at a lever arm L from loop a's query, both loops
/// of sigma 0.2 m / 1 deg: a's heading error also moves b's prediction sideways by L phi_a, so
/// C = [0.08 + L^2 s^2, L s^2; L s^2, 2 s^2] (s = 1 deg), in closed form.
double closedForm(double y, double phi, double lever_m) {
  const double s2 = std::pow(M_PI / 180, 2);
  const double cyy = 0.08 + lever_m * lever_m * s2, cyp = lever_m * s2, cpp = 2 * s2;
  return (y * y * cpp - 2 * y * phi * cyp + phi * phi * cyy) / (cyy * cpp - cyp * cyp);
}

TEST(LoopDisagreementChi2, ALoopsHeadingErrorCountsWithItsLeverArm) {
  const Street street;
  std::mt19937 rng(6);
  PendingLoop a = street.loop(10, 0, rng), b = street.loop(20, 0, rng);  // 20 m apart
  a.relative = between(street.truth[a.match], street.truth[a.query]);
  b.relative = between(street.truth[b.match], street.truth[b.query]);
  EXPECT_LT(loopDisagreementChi2(a, b, street.pose()), 1e-9);
  // Loop a 2 deg off in heading: b predicted 0.70 m sideways and 2 deg turned, mostly what a's
  // heading sigma explains at 20 m (chi^2 2.9, not the 4 of the heading alone).
  const double phi = 2 * M_PI / 180;
  a.relative.phi += phi;
  const double turned = loopDisagreementChi2(a, b, street.pose());
  EXPECT_NEAR(turned, closedForm(20 * std::sin(phi), phi, 20), 0.02);
  EXPECT_LT(turned, 4.0);
  // 0.7 m sideways with the heading right: chi^2 3.5 (b's 0.2 m and the lever arm of a's heading).
  a.relative.phi -= phi;
  b.relative.y -= 0.7;  // b's query frame is turned by 180 deg against its match's
  EXPECT_NEAR(loopDisagreementChi2(a, b, street.pose()), closedForm(0.7, 0, 20), 0.02);
}

TEST(LoopConfirmation, RefusesNonsenseParameters) {
  EXPECT_THROW(LoopConfirmation(1, 3, 16.27), std::invalid_argument);
  EXPECT_THROW(LoopConfirmation(3, 0, 16.27), std::invalid_argument);
  EXPECT_THROW(LoopConfirmation(3, 3, 0), std::invalid_argument);
}

}  // namespace
}  // namespace radarslam::slam_detail
