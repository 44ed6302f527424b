#include "vantage/sim/generate.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "vantage/sim/random.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::sim {
namespace {

/// The pile's draws: the k-th depends on (seed, k) only (random.hpp), so a seed gives the same
/// pile on any machine.
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : seed_(seed) {}

  double uniform() { return uniform_open01(seed_, RandomStream::kPile, next_++); }
  /// A whole number in [lo, hi].
  int whole(int lo, int hi) {
    const int n = hi - lo + 1;
    return lo + std::min(n - 1, static_cast<int>(uniform() * n));
  }
  /// Whole millimetres in [a, a + (b - a) * shrink] with a = lo scale, b = hi scale, as metres.
  double millimetres(int lo, int hi, double shrink, double scale) {
    const int a = static_cast<int>(std::lround(lo * scale));
    const int b = static_cast<int>(std::lround(hi * scale));
    return whole(a, a + static_cast<int>((b - a) * shrink)) / 1000.0;
  }

 private:
  std::uint64_t seed_;
  std::uint64_t next_ = 0;
};

/// An object's size and yaw; sizes' upper ends shrink with `shrink` in (0, 1] as draws fail, and
/// the whole range with `scale` in (0, 1] as rounds of draws fail.
PileObject draw_object(Draws& draws, PileShape shape, double shrink, double scale) {
  PileObject o;
  o.shape = shape;
  switch (o.shape) {
    case PileShape::kBox:
      o.size = {draws.millimetres(40, 180, shrink, scale),
                draws.millimetres(40, 180, shrink, scale),
                draws.millimetres(40, 240, shrink, scale)};
      o.yaw_deg = draws.whole(0, 179);
      break;
    case PileShape::kCylinder: {
      const double r = draws.millimetres(25, 60, shrink, scale);
      o.size = {r, r, draws.millimetres(60, 260, shrink, scale)};
      break;
    }
    case PileShape::kSphere:
      o.size = Eigen::Vector3d::Constant(draws.millimetres(25, 60, shrink, scale));
      break;
    case PileShape::kBunny:
    case PileShape::kTeapot:
      o.size = Eigen::Vector3d::Constant(draws.millimetres(100, 200, shrink, scale));
      o.yaw_deg = draws.whole(0, 359);
      break;
    case PileShape::kDragon:
      o.size = Eigen::Vector3d::Constant(draws.millimetres(120, 240, shrink, scale));
      o.yaw_deg = draws.whole(0, 359);
      break;
  }
  return o;
}

Eigen::Vector2d to_local(const PileObject& box, const Eigen::Vector2d& p) {
  const double yaw = deg2rad(box.yaw_deg);
  const Eigen::Vector2d d = p - box.center;
  return {std::cos(yaw) * d.x() + std::sin(yaw) * d.y(),
          -std::sin(yaw) * d.x() + std::cos(yaw) * d.y()};
}

/// Distance from p to a box's rectangle, 0 inside [m].
double distance_to_box(const PileObject& box, const Eigen::Vector2d& p) {
  const Eigen::Vector2d local = to_local(box, p);
  const double dx = std::max(0.0, std::abs(local.x()) - box.size.x() / 2);
  const double dy = std::max(0.0, std::abs(local.y()) - box.size.y() / 2);
  return std::hypot(dx, dy);
}

/// Whether two footprints come closer than `gap` [m]. Boxes against boxes: separating axes, which
/// may refuse a pair a little farther apart than `gap`, never accept a closer one.
bool too_close(const PileObject& a, const PileObject& b, double gap) {
  if ((a.center - b.center).norm() >= a.radius() + b.radius() + gap) return false;
  const bool a_box = a.shape == PileShape::kBox;
  const bool b_box = b.shape == PileShape::kBox;
  if (!a_box && !b_box) return true;  // two discs: the test above is exact
  if (a_box != b_box) {
    const PileObject& box = a_box ? a : b;
    const PileObject& disc = a_box ? b : a;
    return distance_to_box(box, disc.center) < disc.radius() + gap;
  }
  const auto ca = a.corners();
  const auto cb = b.corners();
  for (const auto* corners : {&ca, &cb}) {
    for (int e = 0; e < 2; ++e) {
      const Eigen::Vector2d axis = ((*corners)[e + 1] - (*corners)[e]).normalized();
      double a_lo = 1e300, a_hi = -1e300, b_lo = 1e300, b_hi = -1e300;
      for (int k = 0; k < 4; ++k) {
        a_lo = std::min(a_lo, ca[k].dot(axis));
        a_hi = std::max(a_hi, ca[k].dot(axis));
        b_lo = std::min(b_lo, cb[k].dot(axis));
        b_hi = std::max(b_hi, cb[k].dot(axis));
      }
      if (a_lo - b_hi >= gap || b_lo - a_hi >= gap) return false;
    }
  }
  return true;
}

/// Whether footprint `o` lies inside footprint `base`.
bool inside(const PileObject& o, const PileObject& base) {
  if (o.shape == PileShape::kBox) {
    const auto corners = o.corners();
    return std::all_of(corners.begin(), corners.end(),
                       [&](const Eigen::Vector2d& p) { return base.covers(p); });
  }
  if (base.shape == PileShape::kBox) {
    const Eigen::Vector2d local = to_local(base, o.center);
    return std::abs(local.x()) + o.radius() <= base.size.x() / 2 &&
           std::abs(local.y()) + o.radius() <= base.size.y() / 2;
  }
  return (o.center - base.center).norm() + o.radius() <= base.radius();
}

/// Whether footprint `o` lies inside the square [-w, w]^2.
bool within(const PileObject& o, double w) {
  if (o.shape == PileShape::kBox) {
    const auto corners = o.corners();
    return std::all_of(corners.begin(), corners.end(), [&](const Eigen::Vector2d& p) {
      return std::abs(p.x()) <= w && std::abs(p.y()) <= w;
    });
  }
  return std::abs(o.center.x()) + o.radius() <= w && std::abs(o.center.y()) + o.radius() <= w;
}

/// A number as the file holds it: millimetres, three decimals.
std::string mm(double metres) { return fmt::format("{:.3f}", metres); }

std::string object_line(const PileObject& o) {
  const std::string xy = fmt::format("{}, {}", mm(o.center.x()), mm(o.center.y()));
  std::string line;
  switch (o.shape) {
    case PileShape::kBox:
      line = fmt::format("{{type: box, size: [{}, {}, {}], pose: [{}, {}, 0, 0, {:.0f}]}}",
                         mm(o.size.x()), mm(o.size.y()), mm(o.size.z()), xy, mm(o.base), o.yaw_deg);
      break;
    case PileShape::kCylinder:
      line = fmt::format("{{type: cylinder, radius: {}, height: {}, pose: [{}, {}]}}",
                         mm(o.size.x()), mm(o.size.z()), xy, mm(o.base));
      break;
    case PileShape::kSphere:  // NOTE: a sphere's pose is its centre
      line = fmt::format("{{type: sphere, radius: {}, pose: [{}, {}]}}", mm(o.size.x()), xy,
                         mm(o.base + o.size.x()));
      break;
    default:
      line = fmt::format("{{type: mesh, model: {}, scale: {}, pose: [{}, {}, 0, 0, {:.0f}]}}",
                         to_string(o.shape), mm(o.size.x()), xy, mm(o.base), o.yaw_deg);
  }
  return line;
}

}  // namespace

std::string_view to_string(PileShape shape) {
  switch (shape) {
    case PileShape::kBox:
      return "box";
    case PileShape::kCylinder:
      return "cylinder";
    case PileShape::kSphere:
      return "sphere";
    case PileShape::kBunny:
      return "bunny";
    case PileShape::kTeapot:
      return "teapot";
    case PileShape::kDragon:
      return "dragon";
  }
  return "?";
}

void PileConfig::validate() const {
  if (objects < 1 || objects > kMaxPileObjects) {
    throw std::invalid_argument(
        fmt::format("pile.objects must be in [1, {}], got {}", kMaxPileObjects, objects));
  }
  if (!(half_width >= 0.1 && half_width <= 0.5)) {
    throw std::invalid_argument(fmt::format(
        "pile.half_width must be in [0.1, 0.5] m (the table's half), got {}", half_width));
  }
  if (!(max_height >= 0.1 && max_height <= 0.5)) {
    throw std::invalid_argument(fmt::format(
        "pile.max_height must be in [0.1, 0.5] m (the grid reaches 0.508 m), got {}", max_height));
  }
  if (!(stack_share >= 0.0 && stack_share <= 1.0)) {
    throw std::invalid_argument(
        fmt::format("pile.stack_share must be in [0, 1], got {}", stack_share));
  }
  if (!(gap >= 0.0 && gap <= 0.1)) {
    throw std::invalid_argument(fmt::format("pile.gap must be in [0, 0.1] m, got {}", gap));
  }
  if (max_attempts < 1) {
    throw std::invalid_argument(
        fmt::format("pile.max_attempts must be >= 1, got {}", max_attempts));
  }
}

double PileObject::height() const {
  switch (shape) {
    case PileShape::kBox:
    case PileShape::kCylinder:
      return size.z();
    case PileShape::kSphere:
      return 2.0 * size.x();
    default:
      return size.x();  // NOTE: a model's largest extent bounds its height
  }
}

double PileObject::radius() const {
  switch (shape) {
    case PileShape::kBox:
      return 0.5 * std::hypot(size.x(), size.y());
    case PileShape::kCylinder:
    case PileShape::kSphere:
      return size.x();
    default:
      // NOTE: centred over its origin with both extents <= scale: inside a disc of scale / sqrt 2.
      return size.x() / std::sqrt(2.0);
  }
}

bool PileObject::covers(const Eigen::Vector2d& p) const {
  if (shape != PileShape::kBox) return (p - center).norm() <= radius();
  const Eigen::Vector2d local = to_local(*this, p);
  return std::abs(local.x()) <= size.x() / 2 && std::abs(local.y()) <= size.y() / 2;
}

std::array<Eigen::Vector2d, 4> PileObject::corners() const {
  const double yaw = deg2rad(yaw_deg);
  const Eigen::Vector2d u(std::cos(yaw) * size.x() / 2, std::sin(yaw) * size.x() / 2);
  const Eigen::Vector2d v(-std::sin(yaw) * size.y() / 2, std::cos(yaw) * size.y() / 2);
  return {center - u - v, center + u - v, center + u + v, center - u + v};
}

std::string pile_name(const PileConfig& config) {
  return fmt::format("pile-{}-s{:04}", config.objects, config.seed);
}

std::string pile_command(const PileConfig& config) {
  return fmt::format("vantage scene generate --objects {} --seed {}", config.objects, config.seed);
}

/// How often an object that finds no place is given another shape.
constexpr int kShapeRounds = 8;

Pile generate_pile(const PileConfig& config) {
  config.validate();
  Pile pile{pile_name(config), config, {}};
  Draws draws(config.seed);
  const int w_mm = static_cast<int>(std::lround(config.half_width * 1000.0));
  const double ceiling = kPileTableHeight + config.max_height;
  std::vector<bool> carries;  // whether an object has another on top
  for (int i = 0; i < config.objects; ++i) {
    // NOTE: the shape is kept while its size and place are drawn until they fit, and drawn again
    // only after each 1 / kShapeRounds of the draws fails: redrawing it each time would favour the
    // small shapes that fit anywhere. Sizes shrink as draws fail, within each round and from round
    // to round (to 0.44 of the usual range in the last), so a crowded table still takes the pile's
    // last objects.
    const int round = std::max(1, config.max_attempts / kShapeRounds);
    PileShape shape = PileShape::kBox;
    // NOTE: decided once per object, so that about stack_share of the objects stand on others
    // where there are bases for them; in each round's second half, table and bases take turns,
    // so a crowded table stacks more.
    const bool stack = draws.uniform() < config.stack_share;
    bool placed = false;
    for (int attempt = 0; attempt < config.max_attempts && !placed; ++attempt) {
      if (attempt % round == 0) {
        shape = static_cast<PileShape>(draws.whole(0, config.meshes ? 5 : 2));
      }
      const double shrink = 1.0 - static_cast<double>(attempt % round) / round;
      const double scale = 1.0 - 0.08 * (attempt / round);
      PileObject o = draw_object(draws, shape, shrink, scale);
      std::vector<int> bases;
      if (attempt % round < round / 2 ? stack : attempt % 2 == 1) {
        for (int j = 0; j < i; ++j) {
          const PileObject& b = pile.objects[static_cast<std::size_t>(j)];
          if (b.stands_on < 0 && !carries[static_cast<std::size_t>(j)] &&
              (b.shape == PileShape::kBox || b.shape == PileShape::kCylinder) &&
              b.top() + o.height() <= ceiling) {
            bases.push_back(j);
          }
        }
      }
      if (!bases.empty()) {
        const int j =
            bases[static_cast<std::size_t>(draws.whole(0, static_cast<int>(bases.size()) - 1))];
        const PileObject& b = pile.objects[static_cast<std::size_t>(j)];
        // Centres from which a disc of the object's radius may still lie on the base's top.
        const double top_radius =
            b.shape == PileShape::kBox ? std::min(b.size.x(), b.size.y()) / 2 : b.radius();
        const int reach = static_cast<int>(std::max(0.0, top_radius - o.radius()) * 1000.0);
        o.center = b.center + Eigen::Vector2d(draws.whole(-reach, reach) / 1000.0,
                                              draws.whole(-reach, reach) / 1000.0);
        o.base = b.top();
        o.stands_on = j;
        placed = inside(o, b);
      } else {
        o.center = {draws.whole(-w_mm, w_mm) / 1000.0, draws.whole(-w_mm, w_mm) / 1000.0};
        o.base = kPileTableHeight;
        placed = o.top() <= ceiling && within(o, config.half_width) &&
                 std::none_of(pile.objects.begin(), pile.objects.end(), [&](const PileObject& p) {
                   return p.stands_on < 0 && too_close(o, p, config.gap);
                 });
      }
      if (placed) {
        if (o.stands_on >= 0) carries[static_cast<std::size_t>(o.stands_on)] = true;
        pile.objects.push_back(o);
        carries.push_back(false);
      }
    }
    if (!placed) {
      throw std::runtime_error(fmt::format(
          "{}: object {} of {} found no place on the table in {} draws; ask for fewer objects",
          pile.name, i + 1, config.objects, config.max_attempts));
    }
  }
  return pile;
}

std::string pile_scene_yaml(const Pile& pile) {
  const PileConfig& c = pile.config;
  std::map<std::string, int> counts;
  for (const PileObject& o : pile.objects) ++counts[std::string(to_string(o.shape))];
  std::string contents;
  for (const auto& [shape, n] : counts) {
    const std::string plural = shape == "box"     ? "boxes"
                               : shape == "bunny" ? "bunnies"
                                                  : shape + "s";
    contents += fmt::format("{}{} {}", contents.empty() ? "" : ", ", n, n == 1 ? shape : plural);
  }
  std::string text = fmt::format(
      "# {}: a pile of {} objects drawn with seed {} by\n"
      "#   {}\n"
      "# (vantage/sim/generate.hpp, docs/scenes.md \"Generated piles\"), which writes the same\n"
      "# file again. Draws: footprints within {} m of the table's centre and {} m apart, tops\n"
      "# at most {} m above the table, {} of the objects set on a box or cylinder, scanned\n"
      "# models {}. Table, grid, sensor, mount and ring as scenes/tabletop-4.yaml.\n"
      "name: {}\n"
      "kind: tabletop\n"
      "description: a generated pile of {} objects (seed {}) - {}\n"
      "units: {{length: m, angle: deg}}\n"
      "\n"
      "grid:\n"
      "  origin: [-0.50390625, -0.50390625, 0.75]\n"
      "  resolution: 0.0078125\n"
      "  dims: [129, 129, 65]\n"
      "\n"
      "floor: {{size: [4, 4]}}\n"
      "table: {{size: [1.0, 1.0], height: 0.75}}\n"
      "\n"
      "objects:\n",
      pile.name, c.objects, c.seed, pile_command(c), c.half_width, c.gap, c.max_height,
      c.stack_share, c.meshes ? "included" : "left out", pile.name, c.objects, c.seed, contents);
  for (std::size_t i = 0; i < pile.objects.size(); ++i) {
    const PileObject& o = pile.objects[i];
    text += fmt::format("  - {}  # {}{}\n", object_line(o), i,
                        o.stands_on >= 0 ? fmt::format(", on {}", o.stands_on) : std::string());
  }
  text +=
      "\n"
      "sensor: hokuyo\n"
      "mount: {height: 1.10, target: [0.0, 0.0, 0.80]}\n"
      "\n"
      "candidates:\n"
      "  generator: ring\n"
      "  radius: 1.0\n"
      "  positions: 10\n"
      "  start_angle_deg: 0\n"
      "  yaw_offsets_deg: [-15, 0, 15]\n"
      "\n"
      "start_poses: ring\n"
      "pose_noise: {x: 0.0, y: 0.0, yaw_deg: 0.0}\n";
  return text;
}

Scene pile_scene(const PileConfig& config) {
  const Pile pile = generate_pile(config);
  return parse_scene(pile_scene_yaml(pile), "generated " + pile.name, ".");
}

}  // namespace vantage::sim
