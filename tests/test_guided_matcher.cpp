// MatcherKind::guided (core/match/guided_matcher.hpp): two synthetic views of a 3D scene, where
// the epipolar band keeps what the whole image's ratio test drops, and nothing else changes.
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "aief/error.hpp"
#include "aief/match.hpp"
#include "core/match/guided_matcher.hpp"

namespace aief {
namespace {

struct Camera {
  double R[9];  // world to camera
  double t[3];
  double f = 900, cx = 500, cy = 400;

  bool project(const double X[3], float& x, float& y) const {
    double c[3];
    for (int r = 0; r < 3; ++r)
      c[r] = R[r * 3] * X[0] + R[r * 3 + 1] * X[1] + R[r * 3 + 2] * X[2] + t[r];
    if (c[2] <= 0.1) return false;
    x = static_cast<float>(f * c[0] / c[2] + cx);
    y = static_cast<float>(f * c[1] / c[2] + cy);
    return x >= 0 && x < 1000 && y >= 0 && y < 800;
  }
};

Camera camera_turned(double yaw, double tx, double ty) {
  Camera cam{};
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double R[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  std::copy(R, R + 9, cam.R);
  cam.t[0] = tx;
  cam.t[1] = ty;
  cam.t[2] = 0;
  return cam;
}

Descriptor random_descriptor(std::mt19937& rng) {
  Descriptor d;
  for (std::uint8_t& byte : d) byte = static_cast<std::uint8_t>(rng());
  return d;
}

Descriptor flipped(Descriptor d, int bits, std::mt19937& rng) {
  std::set<int> chosen;
  while (static_cast<int>(chosen.size()) < bits) chosen.insert(static_cast<int>(rng() % 256));
  for (int bit : chosen) d[static_cast<std::size_t>(bit / 8)] ^= std::uint8_t(1u << (bit % 8));
  return d;
}

// Two views of points at depths 4 to 12. Each seen point's b descriptor is its a descriptor with
// 12 bits flipped. The first `decoyed` points also get a decoy in b, 14 bits from the a
// descriptor, placed 60 px off the point's epipolar line (moved across it): the whole image's
// ratio test (12 < 0.8 x 14 fails) drops these points, the band does not see the decoy.
struct Scene {
  Features a, b;
  std::vector<std::pair<int, int>> truth;  // (index in a, index in b)
  int decoyed = 0;
};

Scene make_scene(int points, int decoyed, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), depth(4, 12);
  const Camera ca = camera_turned(0, 0, 0), cb = camera_turned(0.12, -0.9, 0.15);
  Scene s;
  while (static_cast<int>(s.truth.size()) < points) {
    const double z = depth(rng);
    const double X[3] = {u(rng) * 0.5 * z, u(rng) * 0.4 * z, z};
    Keypoint ka, kb;
    if (!ca.project(X, ka.x, ka.y) || !cb.project(X, kb.x, kb.y)) continue;
    const Descriptor d = random_descriptor(rng);
    s.truth.emplace_back(static_cast<int>(s.a.keypoints.size()),
                         static_cast<int>(s.b.keypoints.size()));
    s.a.keypoints.push_back(ka);
    s.a.descriptors.push_back(d);
    s.b.keypoints.push_back(kb);
    s.b.descriptors.push_back(flipped(d, 12, rng));
    if (static_cast<int>(s.truth.size()) <= decoyed) {
      Keypoint decoy = kb;
      decoy.y = kb.y < 400 ? kb.y + 60 : kb.y - 60;  // epipolar lines run near horizontal here
      s.b.keypoints.push_back(decoy);
      s.b.descriptors.push_back(flipped(d, 14, rng));
    }
  }
  s.decoyed = decoyed;
  return s;
}

std::set<std::pair<int, int>> pairs_of(const std::vector<Match>& matches) {
  std::set<std::pair<int, int>> out;
  for (const Match& m : matches) out.insert({m.query, m.train});
  return out;
}

MatchOptions guided() {
  MatchOptions options;
  options.kind = MatcherKind::guided;
  return options;
}

TEST(GuidedMatcher, KeepsTheMatchesTheWholeImagesRatioTestDrops) {
  const Scene s = make_scene(300, 100, 7);
  MatchOptions mutual_ratio;
  mutual_ratio.kind = MatcherKind::mutual_ratio;
  const auto seeds = pairs_of(match_features(s.a, s.b, mutual_ratio));
  const auto matches = pairs_of(match_features(s.a, s.b, guided()));
  int seeded = 0, found = 0;
  for (int k = 0; k < static_cast<int>(s.truth.size()); ++k) {
    const bool in_seeds = seeds.count(s.truth[static_cast<std::size_t>(k)]) > 0;
    if (k < s.decoyed) {
      EXPECT_FALSE(in_seeds) << "point " << k << " was meant to fail the ratio";
    }
    seeded += in_seeds;
    found += matches.count(s.truth[static_cast<std::size_t>(k)]) > 0;
  }
  EXPECT_EQ(seeded, 200);
  EXPECT_EQ(found, 300);  // every point, the decoyed ones too
  EXPECT_EQ(matches.size(), 300u);
}

TEST(GuidedMatcher, TheBandDecidesWhichCandidatesCompete) {
  const Scene s = make_scene(300, 100, 11);
  MatchOptions wide = guided();
  wide.epipolar_band_px = 64;  // the decoys (60 px across) compete again: their points fail
  const auto matches = pairs_of(match_features(s.a, s.b, wide));
  int decoyed_found = 0;
  for (int k = 0; k < s.decoyed; ++k)
    decoyed_found += matches.count(s.truth[static_cast<std::size_t>(k)]) > 0;
  EXPECT_LT(decoyed_found, 20);
}

TEST(GuidedMatcher, FewSeedsGiveTheSeeds) {
  // 12 seeds (14 points, 2 of them decoyed out of the ratio test): fewer than a matrix needs. A
  // band would find the decoyed two.
  const Scene s = make_scene(14, 2, 5);
  MatchOptions mutual_ratio;
  mutual_ratio.kind = MatcherKind::mutual_ratio;
  EXPECT_EQ(pairs_of(match_features(s.a, s.b, guided())),
            pairs_of(match_features(s.a, s.b, mutual_ratio)));
}

TEST(GuidedMatcher, AMatrixGuidesWithFifteenInliersAndAFifthOfTheSeeds) {
  EXPECT_FALSE(guides(14, 20));
  EXPECT_TRUE(guides(15, 20));
  EXPECT_TRUE(guides(20, 100));
  EXPECT_FALSE(guides(19, 100));
  // Seeds that are mostly wrong: their points agree with no one matrix, the seeds stay.
  Scene s = make_scene(300, 0, 17);
  std::mt19937 rng(4);
  for (int k = 30; k < 300; ++k) {  // 270 of 300 b keypoints moved anywhere
    s.b.keypoints[static_cast<std::size_t>(k)].x = static_cast<float>(rng() % 1000);
    s.b.keypoints[static_cast<std::size_t>(k)].y = static_cast<float>(rng() % 800);
  }
  MatchOptions mutual_ratio;
  mutual_ratio.kind = MatcherKind::mutual_ratio;
  EXPECT_EQ(pairs_of(match_features(s.a, s.b, guided())),
            pairs_of(match_features(s.a, s.b, mutual_ratio)));
}

TEST(GuidedMatcher, OneAndTwoThreadsGiveTheSameMatches) {
  const Scene s = make_scene(600, 200, 13);
  const auto run = [&](int threads) {
    std::vector<Match> out;
    tbb::task_arena(threads).execute([&] { out = match_features(s.a, s.b, guided()); });
    return out;
  };
  const std::vector<Match> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].query, two[k].query);
    EXPECT_EQ(one[k].train, two[k].train);
    EXPECT_EQ(one[k].distance, two[k].distance);
  }
}

TEST(GuidedMatcher, BandMatchingFollowsTheSampsonDistance) {
  // F of a pure sideways move (x_b = x_a + d): lines are the rows y_b = y_a; Sampson distance of
  // (x, y) <-> (u, v) is |v - y| / sqrt(2).
  const Fundamental F = {0, 0, 0, 0, 0, -1, 0, 1, 0};
  std::mt19937 rng(3);
  Features a, b;
  const Descriptor d = random_descriptor(rng);
  a.keypoints.push_back({100, 200});
  a.descriptors.push_back(d);
  b.keypoints.push_back({300, 201.5f});  // Sampson 1.06 px: outside a 1 px band
  b.descriptors.push_back(flipped(d, 2, rng));
  b.keypoints.push_back({40, 200.9f});  // 0.64 px: inside
  b.descriptors.push_back(flipped(d, 30, rng));
  MatchOptions options = guided();
  std::vector<Match> m = match_in_epipolar_band(a, b, F, options);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].train, 1);
  options.epipolar_band_px = 1.1;  // both inside: the nearer descriptor wins, the ratio passes
  m = match_in_epipolar_band(a, b, F, options);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].train, 0);
  options.max_distance = 1;  // and max_distance still applies
  EXPECT_TRUE(match_in_epipolar_band(a, b, F, options).empty());
}

TEST(GuidedMatcher, NeedsKeypoints) {
  const Scene s = make_scene(50, 0, 9);
  try {
    match_descriptors(s.a.descriptors, s.b.descriptors, guided());
    FAIL() << "guided matched descriptors alone";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needs the keypoints"), std::string::npos) << e.what();
  }
  Features no_keypoints = s.a;
  no_keypoints.keypoints.pop_back();
  EXPECT_THROW(match_features(no_keypoints, s.b, guided()), Error);
  MatchOptions bad = guided();
  bad.epipolar_band_px = 0;
  EXPECT_THROW(match_features(s.a, s.b, bad), Error);
  // A keypoint at infinity would be on every epipolar line: refused, naming it.
  Features far = s.b;
  far.keypoints[3].x = std::numeric_limits<float>::infinity();
  try {
    match_features(s.a, far, guided());
    FAIL() << "a keypoint at infinity was matched";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("keypoint 3 of the second features"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace aief
