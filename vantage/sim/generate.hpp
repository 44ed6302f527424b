#pragma once
/// @file
/// Generated clutter: seeded piles of the scanned models (bunny, teapot, dragon) and primitives
/// (box, cylinder, sphere) on the paper's table, with the grid, sensor, mount and 30-view ring of
/// the built-in table tops (scenes/tabletop-4.yaml). The same settings give the same scene file,
/// byte for byte, on any machine (docs/scenes.md, "Generated piles").

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/sim/scene.hpp"

namespace vantage::sim {

/// The most objects a pile holds: more do not fit on the table at these sizes.
inline constexpr int kMaxPileObjects = 30;

/// What a pile is drawn from. Sizes and positions are drawn in whole millimetres and yaws in
/// whole degrees, so the file's numbers are exact.
struct PileConfig {
  int objects = 12;           ///< objects in the pile, 1..kMaxPileObjects
  std::uint64_t seed = 1;     ///< the same seed gives the same file
  double half_width = 0.4;    ///< footprints lie within [-w, w]^2 of the table's centre [m]
  double max_height = 0.4;    ///< tops stay this far above the table at most (grid: 0.508) [m]
  double stack_share = 0.25;  ///< chance that an object is set on a box or cylinder, in [0, 1]
  double gap = 0.005;         ///< least clearance between the footprints on the table [m]
  bool meshes = true;         ///< draw the scanned models too (false: primitives only)
  int max_attempts = 16000;   ///< draws per object before giving up

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// What an object of a pile is.
enum class PileShape { kBox, kCylinder, kSphere, kBunny, kTeapot, kDragon };
std::string_view to_string(PileShape shape);

/// One object of a pile. Its footprint is its outline seen from above: a box's rectangle, a
/// cylinder's or sphere's disc, and for a scanned model the disc that holds it at any yaw (the
/// model is centred over its origin and its largest extent is `scale`, docs/scenes.md).
struct PileObject {
  PileShape shape = PileShape::kBox;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< of the footprint (x, y) [m]
  double base = 0.0;                                 ///< height of its bottom above the floor [m]
  double yaw_deg = 0.0;                              ///< turn about z, whole degrees [deg]
  /// Box: edges x, y, z; cylinder: radius, radius, height; sphere: radius x 3; model: its scale
  /// (largest extent) x 3 [m].
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  int stands_on = -1;  ///< index of the object it stands on; -1: the table

  /// Height above `base` that it reaches at most [m].
  double height() const;
  double top() const { return base + height(); }
  /// Whether its footprint holds the point (x, y) [m].
  bool covers(const Eigen::Vector2d& p) const;
  /// Radius of the disc its footprint is (cylinder, sphere, model), or of the disc around a box's
  /// rectangle [m].
  double radius() const;
  /// A box's footprint corners, counter-clockwise [m].
  std::array<Eigen::Vector2d, 4> corners() const;
};

/// A generated pile and the settings that made it.
struct Pile {
  std::string name;  ///< pile_name(config)
  PileConfig config;
  std::vector<PileObject> objects;
};

/// The height of the paper's table top above the floor [m].
inline constexpr double kPileTableHeight = 0.75;

/// "pile-12-s0007": the objects and the seed, the seed zero-padded to 4 digits.
std::string pile_name(const PileConfig& config);

/// Draws a pile: each object's shape, then its size, yaw and place by rejection sampling, sizes
/// shrinking as draws fail (and a new shape, in a smaller range, after each eighth of
/// max_attempts), on the table or (with chance stack_share, or where the table is full) on top of
/// a box or cylinder standing on the table, one object on each at most. No two footprints on the
/// table come closer than `gap`; an object set on another lies inside that one's top. Throws
/// std::invalid_argument for a bad config and std::runtime_error when an object finds no place in
/// max_attempts draws.
Pile generate_pile(const PileConfig& config);

/// The scene file of a pile (docs/scenes.md): tabletop-4's table, grid, sensor, mount, ring and
/// starts, the pile's objects, and a header that names the command that writes it.
std::string pile_scene_yaml(const Pile& pile);

/// The scene of a pile, parsed from pile_scene_yaml; `source` is "generated <name>". Throws what
/// parse_scene throws (a scanned model that is not fetched).
Scene pile_scene(const PileConfig& config);

/// The command line that writes a pile's scene file (its reproducible source).
std::string pile_command(const PileConfig& config);

}  // namespace vantage::sim
