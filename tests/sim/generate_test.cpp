// Generated piles: the same seed gives the same file, every object stands on the table inside
// the grid, footprints on the table keep apart (checked point by point against the generator's
// separating-axis test), and the file loads as the paper's table top.

#include "vantage/sim/generate.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

namespace vantage::sim {
namespace {

PileConfig pile(int objects, std::uint64_t seed) {
  PileConfig config;
  config.objects = objects;
  config.seed = seed;
  return config;
}

TEST(GeneratePile, SameSeedSameTextOtherSeedsDiffer) {
  const std::string a = pile_scene_yaml(generate_pile(pile(12, 7)));
  EXPECT_EQ(a, pile_scene_yaml(generate_pile(pile(12, 7))));
  EXPECT_NE(a, pile_scene_yaml(generate_pile(pile(12, 8))));
  EXPECT_NE(a, pile_scene_yaml(generate_pile(pile(13, 7))));
  EXPECT_NE(a.find("name: pile-12-s0007\n"), std::string::npos);
  EXPECT_NE(a.find("\n#   vantage scene generate --objects 12 --seed 7\n"), std::string::npos);
  // The first draws do not depend on how many objects follow.
  const Pile few = generate_pile(pile(3, 7));
  const Pile more = generate_pile(pile(12, 7));
  EXPECT_EQ(few.objects[0].center, more.objects[0].center);
  EXPECT_EQ(few.objects[0].size, more.objects[0].size);
}

TEST(GeneratePile, ObjectsStayOnTheTableAndApart) {
  std::size_t stacked = 0;
  std::set<int> yaws;
  std::set<PileShape> shapes;
  for (const int objects : {1, 12, 30}) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      const Pile p = generate_pile(pile(objects, seed));
      SCOPED_TRACE(p.name);
      ASSERT_EQ(p.objects.size(), static_cast<std::size_t>(objects));
      for (std::size_t i = 0; i < p.objects.size(); ++i) {
        const PileObject& o = p.objects[i];
        shapes.insert(o.shape);
        yaws.insert(static_cast<int>(o.yaw_deg));
        EXPECT_LE(o.top(), kPileTableHeight + p.config.max_height + 1e-12) << i;
        if (o.stands_on < 0) {
          EXPECT_EQ(o.base, kPileTableHeight) << i;
        } else {
          ++stacked;
          ASSERT_LT(o.stands_on, static_cast<int>(i));
          const PileObject& b = p.objects[static_cast<std::size_t>(o.stands_on)];
          EXPECT_EQ(b.stands_on, -1) << "one level of stacking only";
          EXPECT_EQ(o.base, b.top()) << i;
        }
      }
      // Point by point over the table, 4 mm apart: at most one object on the table covers a
      // point, inside the footprint square; an object on another covers only its base's points.
      const double w = p.config.half_width;
      for (double x = -0.5; x <= 0.5; x += 0.004) {
        for (double y = -0.5; y <= 0.5; y += 0.004) {
          const Eigen::Vector2d q(x, y);
          int on_table = 0;
          for (const PileObject& o : p.objects) {
            if (!o.covers(q)) continue;
            if (o.stands_on < 0) {
              ++on_table;
              EXPECT_LE(std::abs(x), w + 1e-9);
              EXPECT_LE(std::abs(y), w + 1e-9);
            } else {
              EXPECT_TRUE(p.objects[static_cast<std::size_t>(o.stands_on)].covers(q))
                  << "(" << x << ", " << y << ")";
            }
          }
          ASSERT_LE(on_table, 1) << "footprints overlap at (" << x << ", " << y << ")";
        }
      }
    }
  }
  EXPECT_GT(stacked, 0u) << "no object was ever set on another";
  EXPECT_EQ(shapes.size(), 6u);
  EXPECT_GT(yaws.size(), 50u);
}

// The file loads as a table top with tabletop-4's grid, sensor, ring and starts, and every
// object's geometry (the scanned models' meshes included) lies over the table and in the grid.
TEST(GeneratePile, LoadsAsATableTopInsideTheGrid) {
  const Scene reference = load_scene("tabletop-4");
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Scene scene = pile_scene(pile(12, seed));
    SCOPED_TRACE(scene.name);
    EXPECT_EQ(scene.name, "pile-12-s" + std::string(3, '0') + std::to_string(seed));
    EXPECT_EQ(scene.kind, SceneKind::kTableTop);
    EXPECT_EQ(scene.grid, reference.grid);
    EXPECT_EQ(scene.sensor.name, reference.sensor.name);
    EXPECT_EQ(scene.candidate_poses().size(), 30u);
    ASSERT_EQ(scene.start_poses.size(), reference.start_poses.size());
    for (std::size_t k = 0; k < scene.start_poses.size(); ++k) {
      EXPECT_TRUE(scene.start_poses[k].isApprox(reference.start_poses[k]));
    }
    // tabletop-4: 17 objects in 19 shapes, the floor and the table besides.
    ASSERT_EQ(scene.shapes.size(), 12u + reference.shapes.size() - 17u);
    Eigen::AlignedBox3d grid(scene.grid.origin, scene.grid.max_corner());
    for (std::size_t k = reference.shapes.size() - 17u; k < scene.shapes.size(); ++k) {
      const Eigen::AlignedBox3d box = scene.shapes[k].bounds();
      EXPECT_TRUE(grid.contains(box)) << scene.shapes[k].name;
      EXPECT_GE(box.min().z(), kPileTableHeight - 1e-9) << scene.shapes[k].name;
      EXPECT_LE(box.max().cwiseAbs().head<2>().maxCoeff(), 0.5) << scene.shapes[k].name;
    }
  }
}

TEST(GeneratePile, RefusesBadSettingsNamingTheField) {
  for (const int objects : {0, -3, kMaxPileObjects + 1}) {
    try {
      generate_pile(pile(objects, 1));
      FAIL() << objects << " objects accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("pile.objects"), std::string::npos) << e.what();
    }
  }
  PileConfig wide = pile(12, 1);
  wide.half_width = 0.6;
  EXPECT_THROW(generate_pile(wide), std::invalid_argument);
}

}  // namespace
}  // namespace vantage::sim
