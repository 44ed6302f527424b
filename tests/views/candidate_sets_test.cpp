// The candidate sets' registry (vantage/views/candidate_sets.hpp) and the travel on an object's
// view sphere (vantage/views/travel.hpp).

#include "vantage/views/candidate_sets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

namespace vantage {
namespace {

CandidateSite site_around(const Eigen::Vector3d& target) {
  CandidateSite site;
  site.target = target;
  site.region = Eigen::AlignedBox3d(target - Eigen::Vector3d(0.5, 0.5, 0.2),
                                    target + Eigen::Vector3d(0.5, 0.5, 0.2));
  return site;
}

TEST(CandidateSets, EveryRowIsNamedOnceAndFoundByItsName) {
  std::set<std::string> names;
  for (const CandidateSetRow& row : candidate_sets()) {
    EXPECT_FALSE(row.help.empty()) << row.name;
    EXPECT_TRUE(names.insert(std::string(row.name)).second) << row.name << " twice";
    EXPECT_EQ(&find_candidate_set(row.name), &row);
    EXPECT_TRUE(is_candidate_set(row.name));
  }
  for (const char* name :
       {"ring", "hemisphere", "sphere", "view-sphere", "frontier", "stops", "file"}) {
    EXPECT_TRUE(names.count(name)) << name;
  }
  try {
    (void)find_candidate_set("cube");
    FAIL() << "an unknown set was found";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown candidate set 'cube' (expected one of: ring,"),
              std::string::npos)
        << e.what();
  }
}

TEST(CandidateSets, EverySetPlacedAroundATargetLooksAtIt) {
  const Eigen::Vector3d target(0.3, -0.2, 0.8);
  for (const CandidateSetRow& row : candidate_sets()) {
    if (row.needs_map || row.needs_list) continue;
    const PlacedViews views = row.build(site_around(target), CandidateParams{});
    ASSERT_FALSE(views.poses.empty()) << row.name;
    for (const Eigen::Isometry3d& pose : views.poses) {
      const Eigen::Vector3d to_target = (target - pose.translation()).normalized();
      // The ring's yaw offsets turn a view up to 15 degrees off its target.
      EXPECT_GT(pose.linear().col(0).dot(to_target), std::cos(0.27)) << row.name;
    }
  }
}

TEST(CandidateSets, TheListedSetIsTheUsersPosesAndTheFrontierNeedsAMap) {
  CandidateParams params;
  params.listed = {Eigen::Isometry3d(Eigen::Translation3d(1, 2, 3)), Eigen::Isometry3d::Identity()};
  const PlacedViews views = build_candidates("file", CandidateSite{}, params);
  ASSERT_EQ(views.poses.size(), 2u);
  EXPECT_TRUE(views.poses[0].isApprox(params.listed[0]));
  EXPECT_THROW(build_candidates("file", CandidateSite{}, CandidateParams{}), std::invalid_argument);
  EXPECT_THROW(build_candidates("frontier", CandidateSite{}, CandidateParams{}),
               std::invalid_argument);
}

TEST(CandidateSets, TheViewSphereCoversTheWholeSphereEvenly) {
  const Eigen::Vector3d center(0.1, 0.2, 0.3);
  CandidateSite site = site_around(center);
  site.sphere = object_view_sphere(center, 0.7);
  const PlacedViews views = build_candidates("view-sphere", site, CandidateParams{});
  ASSERT_EQ(views.poses.size(), 32u);  // SCVP's and MA-SCVP's
  EXPECT_EQ(views.travel.kind, TravelRule::Kind::kSphereArc);
  int below = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double nearest_pair = 10.0;
  for (std::size_t i = 0; i < views.poses.size(); ++i) {
    const Eigen::Vector3d offset = views.poses[i].translation() - center;
    EXPECT_NEAR(offset.norm(), 0.7, 1e-12);
    EXPECT_NEAR(views.poses[i].linear().col(0).dot(-offset.normalized()), 1.0, 1e-12);
    below += offset.z() < 0.0 ? 1 : 0;
    mean += offset;
    for (std::size_t j = 0; j < i; ++j) {
      nearest_pair = std::min(nearest_pair,
                              (views.poses[i].translation() - views.poses[j].translation()).norm());
    }
  }
  EXPECT_EQ(below, 16);                       // half below the object's centre
  EXPECT_LT(mean.norm() / 32.0, 0.05 * 0.7);  // no side favoured
  // 32 points evenly spread on a sphere of 0.7 m lie about 0.22 m apart; none nearly coincide.
  EXPECT_GT(nearest_pair, 0.15);
  CandidateParams params;
  params.views = 100;
  params.radius = 1.0;
  EXPECT_EQ(build_candidates("view-sphere", site, params).poses.size(), 100u);
}

// A 10 x 10 x 3 grid of 1 m cells: a free room x <= 4 with an occupied column at (4, 5), a free
// pocket x >= 7, y <= 2, the rest unknown; its frontier regions on the middle layer are the room's
// face x = 4 south and north of the column and the pocket's rim.
CandidateSite office_site() {
  static const OccupancyGrid grid = [] {
    OccupancyGrid g(GridSpec{Eigen::Vector3d::Zero(), 1.0, {10, 10, 3}});
    for (int z = 0; z < 3; ++z) {
      for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 10; ++x) {
          const std::size_t i = g.spec().linear({x, y, z});
          if (x == 4 && y == 5) {
            g.set_probability(i, 0.9);
          } else if (x <= 4 || (x >= 7 && y <= 2)) {
            g.set_probability(i, 0.2);
          }
        }
      }
    }
    return g;
  }();
  CandidateSite site;
  site.grid = &grid;
  GroundRobot& robot = site.robot.emplace();
  robot.position = Eigen::Vector2d(1.5, 1.5);
  robot.navigation.footprint = 0.5;
  robot.navigation.min_height = 0.0;
  robot.navigation.max_height = 3.0;
  robot.frontier.min_z = robot.frontier.max_z = 1.5;
  robot.frontier.min_cells = 1;
  robot.frontier.max_radius = 0.0;
  robot.sensor_pose = [](double x, double y, double yaw) {
    Eigen::Isometry3d pose(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    pose.translation() = Eigen::Vector3d(x, y, 1.2);
    return pose;
  };
  return site;
}

TEST(CandidateSets, AnOfficesStopsAreItsUnvisitedFrontiersWithTheirDrivesOnTheMap) {
  CandidateSite site = office_site();
  const GroundRobot& robot = *site.robot;
  const PlacedViews stops = build_candidates("stops", site, CandidateParams{});
  const std::vector<FrontierRegion> regions = frontier_regions(*site.grid, robot.frontier);
  ASSERT_EQ(regions.size(), 3u);
  ASSERT_EQ(stops.poses.size(), 3u);
  ASSERT_EQ(stops.drives.size(), 3u);
  const NavigationGrid nav = NavigationGrid::from_map(*site.grid, robot.navigation);
  const TravelMap travel(nav, robot.position);
  for (std::size_t k = 0; k < stops.poses.size(); ++k) {
    const Drive& drive = stops.drives[k];
    EXPECT_TRUE(drive.reachable) << k;
    EXPECT_TRUE(drive.arrival.isApprox(drive.goal)) << k;
    // The drive is the map's shortest path, and the robot faces the way it drove.
    EXPECT_DOUBLE_EQ(drive.length, travel.distance(*nav.cell_of(drive.arrival))) << k;
    const Eigen::Vector2d way = drive.goal - robot.position;
    EXPECT_TRUE(stops.poses[k].isApprox(
        robot.sensor_pose(drive.goal.x(), drive.goal.y(), std::atan2(way.y(), way.x()))))
        << k;
  }
  // A stop taken is not offered again.
  site.robot->visited = {stops.drives[1].arrival + Eigen::Vector2d(0.2, 0.0)};
  const PlacedViews left = build_candidates("stops", site, CandidateParams{});
  ASSERT_EQ(left.poses.size(), 2u);
  EXPECT_TRUE(left.drives[0].goal.isApprox(stops.drives[0].goal));
  EXPECT_TRUE(left.drives[1].goal.isApprox(stops.drives[2].goal));
}

TEST(CandidateSets, StopsNeedAGroundRobotAndItsMap) {
  CandidateSite site = office_site();
  EXPECT_TRUE(find_candidate_set("stops").needs_robot);
  site.robot.reset();
  EXPECT_THROW(build_candidates("stops", site, CandidateParams{}), std::invalid_argument);
  EXPECT_THROW(build_candidates("stops", CandidateSite{}, CandidateParams{}),
               std::invalid_argument);
}

TEST(Travel, TheSphereArcIsAMetricAboveTheChordAndAtMostHalfAGreatCircle) {
  const TravelRule arc{TravelRule::Kind::kSphereArc, Eigen::Vector3d(0.5, -1, 2), 0.7};
  std::mt19937 rng(7);
  std::normal_distribution<double> n;
  auto point = [&] {
    return arc.center + arc.radius * Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
  };
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d a = point(), b = point(), c = point();
    const double ab = arc(a, b);
    EXPECT_GE(ab, (a - b).norm() - 1e-12);
    EXPECT_LE(ab, std::numbers::pi * arc.radius + 1e-12);
    EXPECT_NEAR(ab, arc(b, a), 1e-12);
    EXPECT_LE(ab, arc(a, c) + arc(c, b) + 1e-12);
  }
  const Eigen::Vector3d top = arc.center + Eigen::Vector3d(0, 0, 0.7);
  const Eigen::Vector3d bottom = arc.center - Eigen::Vector3d(0, 0, 0.7);
  const Eigen::Vector3d side = arc.center + Eigen::Vector3d(0.7, 0, 0);
  EXPECT_NEAR(arc(top, bottom), std::numbers::pi * 0.7, 1e-12);  // around, never through
  EXPECT_NEAR(arc(top, side), std::numbers::pi / 2 * 0.7, 1e-12);
  EXPECT_NEAR(arc(top, top), 0.0, 1e-12);
}

/// The length of a polyline [m].
double length_of(const std::vector<Eigen::Vector3d>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  return length;
}

TEST(Travel, ThePathGoesAroundTheCentreAndIsAsLongAsTheTravel) {
  const Eigen::Vector3d center(0.5, -1, 2);
  const double radius = 0.7, step = 0.02;
  std::mt19937 rng(11);
  std::normal_distribution<double> n;
  for (const TravelRule::Kind kind : {TravelRule::Kind::kStraightLine, TravelRule::Kind::kRingWalk,
                                      TravelRule::Kind::kSphereArc}) {
    const TravelRule rule{kind, center, radius};
    const bool ring = kind == TravelRule::Kind::kRingWalk;
    auto point = [&] {
      if (!ring)
        return Eigen::Vector3d(center +
                               radius * Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized());
      const Eigen::Vector2d d = Eigen::Vector2d(n(rng), n(rng)).normalized() * radius;
      return Eigen::Vector3d(center.x() + d.x(), center.y() + d.y(), center.z() + 0.25);
    };
    for (int k = 0; k < 500; ++k) {
      const Eigen::Vector3d a = point(), b = point();
      const std::vector<Eigen::Vector3d> path = rule.path(a, b, step);
      ASSERT_GE(path.size(), 2u);
      EXPECT_EQ(path.front(), a);
      EXPECT_EQ(path.back(), b);
      for (std::size_t i = 1; i < path.size(); ++i) {
        EXPECT_LE((path[i] - path[i - 1]).norm(), step + 1e-9);
        const Eigen::Vector3d d = path[i] - center;
        // Around the object, never through it: the sphere's and the ring's points stay at the
        // radius (the ring's horizontally).
        if (kind == TravelRule::Kind::kSphereArc) {
          EXPECT_NEAR(d.norm(), radius, 1e-9);
        } else if (ring) {
          EXPECT_NEAR(d.head<2>().norm(), radius, 1e-9);
        }
      }
      // The chords fall short of the arc by about (step / radius)^2 / 24 of it.
      const double travel = rule(a, b), drawn = length_of(path);
      EXPECT_LE(drawn, travel + 1e-9);
      EXPECT_GE(drawn, travel * (1.0 - 1e-3));
    }
  }
  const TravelRule sphere{TravelRule::Kind::kSphereArc, center, radius};
  const Eigen::Vector3d top = center + Eigen::Vector3d(0, 0, radius);
  const std::vector<Eigen::Vector3d> around =
      sphere.path(top, center - Eigen::Vector3d(0, 0, radius));
  EXPECT_NEAR(length_of(around), std::numbers::pi * radius, 1e-3);  // opposite: half a circle
  EXPECT_THROW(sphere.path(top, top, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
