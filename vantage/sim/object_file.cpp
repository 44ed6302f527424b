// The object file (docs/objects.md): meshes and their poses under the object protocol, read by
// io's one strict YAML reader into an object scene (object_scene.hpp).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "vantage/sim/detail/scene_values.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim::detail {

Scene parse_object_file(const YamlField& root, const std::filesystem::path& base_dir) {
  root.allow_keys({"name", "kind", "description", "units", "objects", "protocol"});
  if (auto units = root.get("units")) check_units(*units);
  ObjectProtocol protocol;
  if (auto p = root.get("protocol")) {
    p->allow_keys({"object_radius", "view_radius", "views", "resolution", "sensor"});
    protocol.object_radius = positive_or(*p, "object_radius", protocol.object_radius);
    protocol.view_radius = positive_or(*p, "view_radius", protocol.view_radius);
    if (auto v = p->get("views")) protocol.views = v->integer(1, 100000);
    protocol.resolution = positive_or(*p, "resolution", protocol.resolution);
    if (auto v = p->get("sensor")) protocol.sensor = v->text();
    try {
      protocol.validate();
    } catch (const std::invalid_argument& e) {
      p->fail(e.what());
    }
  }
  const YamlField list = root.at("objects");
  const auto items = list.items();
  if (items.empty()) list.fail("needs at least one object");
  if (items.size() > kMaxSceneObjects) {
    list.fail(cat("holds ", items.size(), " objects, more than the ", kMaxSceneObjects,
                  " a scene may place"));
  }
  std::vector<ObjectPlacement> objects;
  for (const YamlField& item : items) {
    item.allow_keys({"file", "model", "radius", "pose"});
    const auto model = item.get("model");
    const auto file = item.get("file");
    if (model.has_value() == file.has_value()) {
      item.fail("an object needs exactly one of 'model' or 'file'");
    }
    ObjectPlacement o;
    o.mesh = model ? model->text() : file->text();
    if (file && std::filesystem::path(o.mesh).is_relative()) o.mesh = (base_dir / o.mesh).string();
    o.radius = positive_or(item, "radius", protocol.object_radius);
    if (auto pose = item.get("pose")) o.pose = parse_pose(*pose);
    objects.push_back(o);
  }
  try {
    return object_scene(root.at("name").text(), objects, protocol, base_dir);
  } catch (const std::invalid_argument& e) {
    list.fail(e.what());
  } catch (const std::runtime_error& e) {
    list.fail(e.what());
  }
}

}  // namespace vantage::sim::detail
