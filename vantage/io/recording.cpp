#include "vantage/io/recording.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/recording_formats.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

bool is_type(std::string_view type, std::string_view package, std::string_view name) {
  return type == cat(package, "/", name) || type == cat(package, "/msg/", name);
}

/// tf's tree over the recording: per child frame its parent and its poses there.
class TfTree {
 public:
  void add(const RosTransform& t, bool is_static) {
    Edge& edge = edges_[t.child];
    edge.parent = t.header.frame_id;
    edge.is_static = edge.is_static || is_static;
    edge.samples.push_back({t.header.stamp, t.T_parent_child});
  }
  /// Sorts each edge's samples by stamp, the last of equal stamps kept.
  void finish() {
    for (auto& [child, edge] : edges_) {
      std::stable_sort(
          edge.samples.begin(), edge.samples.end(),
          [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
      std::vector<StampedPose> unique;
      for (const StampedPose& s : edge.samples) {
        if (!unique.empty() && unique.back().stamp == s.stamp) unique.pop_back();
        unique.push_back(s);
      }
      edge.samples = std::move(unique);
    }
  }
  /// Every frame tf names, as a child or as a parent, sorted.
  std::set<std::string> frames() const {
    std::set<std::string> names;
    for (const auto& [child, edge] : edges_) {
      names.insert(child);
      names.insert(edge.parent);
    }
    return names;
  }
  /// The root of `frame`'s chain of parents.
  std::string root(std::string frame) const {
    for (int depth = 0; depth < kMaxDepth; ++depth) {
      const auto it = edges_.find(frame);
      if (it == edges_.end()) return frame;
      frame = it->second.parent;
    }
    return frame;
  }
  /// T_fixed_frame at `stamp`, or nothing.
  std::optional<Eigen::Isometry3d> lookup(std::string frame, const std::string& fixed, double stamp,
                                          double max_dt) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int depth = 0; depth < kMaxDepth && frame != fixed; ++depth) {
      const auto it = edges_.find(frame);
      if (it == edges_.end()) return std::nullopt;
      const Edge& edge = it->second;
      std::optional<Eigen::Isometry3d> step;
      if (edge.is_static) {
        step = edge.samples.back().T_world_frame;
      } else {
        step = interpolate_pose(edge.samples, stamp, max_dt);
      }
      if (!step) return std::nullopt;
      T = *step * T;
      frame = edge.parent;
    }
    if (frame != fixed) return std::nullopt;
    return T;
  }

 private:
  static constexpr int kMaxDepth = 64;  ///< a longer chain is a cycle
  struct Edge {
    std::string parent;
    bool is_static = false;
    std::vector<StampedPose> samples;
  };
  std::map<std::string, Edge, std::less<>> edges_;
};

/// The one line a damaged recording is refused with: the damage, and the frames before it.
std::string damage_line(const RecordingDamage& damage, const std::string& topic, std::size_t listed,
                        double last_stamp, const RecordingIndex& index) {
  std::string frames = "no whole frame of " + printable(topic, 60) + " lies before it";
  if (listed > 0) {
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "%.6f", last_stamp);
    frames = cat("the last whole frame before it is frame ", listed, " of ", printable(topic, 60),
                 " (stamp ", stamp, " s)");
  }
  const auto total = index.find(topic);
  if (total != index.end()) frames += cat(", of the ", total->second, " its index counts");
  return cat(damage.what(), "; ", frames,
             listed > 0 ? "; --salvage maps the frames before it" : "");
}

/// The recording's messages as they are read: the frames of the topic (every `every`-th), its
/// depth images and camera infos, tf, and every topic's type.
struct Listing {
  explicit Listing(const RecordingOptions& given)
      : options(given),
        info_topic(!given.camera_info.empty()
                       ? given.camera_info
                       : given.topic.substr(0, given.topic.rfind('/') + 1) + "camera_info") {}

  /// Takes one message, in the recording's order; what is wrong with it names it.
  void take(const RecordedMessage& m) {
    const std::size_t frames_before = frames.size();
    ++index;
    topics.emplace(m.topic, m.type);
    try {
      decode(m);
    } catch (const FormatError& e) {
      throw FormatError(cat("message ", index, " (", printable(m.topic, 60), " at ", m.log_time,
                            " s): ", e.what()));
    }
    if (frames.size() > frames_before) last_stamp = frames.back().stamp;
  }

  const RecordingOptions& options;
  const std::string info_topic;
  std::vector<RecordingFrame> frames;
  std::map<std::string, std::string, std::less<>> topics;  // topic: type
  TfTree tf;
  std::size_t listed = 0;  ///< messages on the topic
  std::size_t index = 0;   ///< messages
  std::vector<RosDepthImage> images;
  std::vector<RosCameraInfo> infos;
  double last_stamp = 0.0;  ///< [s] of the last frame listed

 private:
  void decode(const RecordedMessage& m) {
    if (m.topic == options.topic) {
      const bool image = is_type(m.type, "sensor_msgs", "Image");
      if (!image && !is_type(m.type, "sensor_msgs", "PointCloud2")) {
        throw FormatError(cat("topic ", options.topic, " holds ", printable(m.type, 60),
                              ", not sensor_msgs/PointCloud2 or sensor_msgs/Image"));
      }
      if (listed++ % static_cast<std::size_t>(options.every) != 0) return;
      if (image) {
        images.push_back(decode_depth_image(m.data, m.encoding));
        frames.push_back(
            {images.back().header.stamp, images.back().header.frame_id, {}, 0, std::nullopt});
        return;
      }
      RosCloud cloud = decode_point_cloud2(m.data, m.encoding);
      frames.push_back({cloud.header.stamp, std::move(cloud.header.frame_id),
                        std::move(cloud.points), cloud.non_finite, std::nullopt});
    } else if (m.topic == info_topic && is_type(m.type, "sensor_msgs", "CameraInfo")) {
      infos.push_back(decode_camera_info(m.data, m.encoding));
    } else if ((m.topic == "/tf" || m.topic == "/tf_static") &&
               is_type(m.type, "tf2_msgs", "TFMessage")) {
      for (const RosTransform& t : decode_tf_message(m.data, m.encoding)) {
        tf.add(t, m.topic == "/tf_static");
      }
    }
  }
};

void check_options(const RecordingOptions& options) {
  if (options.topic.empty()) throw std::invalid_argument("give the recording's topic");
  if (options.every < 1)
    throw std::invalid_argument(cat("every must be >= 1, got ", options.every));
  if (!(options.max_time_difference > 0.0)) {
    throw std::invalid_argument(
        cat("max_time_difference must be positive, got ", options.max_time_difference));
  }
}

/// The recording's bytes, when it is named as one and it and its frames fit in memory.
std::string read_whole(const std::filesystem::path& path, const std::string& ext) {
  if (ext != ".bag" && ext != ".mcap") {
    throw FormatError("not a recording: give a ROS 1 bag (.bag) or an MCAP file (.mcap)");
  }
  // NOTE: read whole: the file, then its frames' points (about twice its size), must fit.
  const std::uintmax_t size = require_input_file(path, InputKind::kRecording);
  if (const std::uint64_t available = available_memory();
      available > 0 && 3.0 * static_cast<double>(size) > static_cast<double>(available)) {
    throw FormatError(cat("is ", describe_bytes(static_cast<double>(size)),
                          ", and reading it needs about three times that, more than the ",
                          describe_bytes(static_cast<double>(available)),
                          " this machine has available"));
  }
  return read_input_file(path, InputKind::kRecording);
}

/// Reads every message into `listing`; a damaged recording is refused, or with `salvage` its
/// frames before the damage kept and what was dropped returned.
std::optional<RecordingSalvage> list_messages(const std::string& bytes, const std::string& ext,
                                              Listing& listing) {
  const RecordingOptions& options = listing.options;
  const auto take = [&](const RecordedMessage& m) { listing.take(m); };
  try {
    if (ext == ".bag") {
      read_rosbag(bytes, take);
    } else {
      read_mcap(bytes, take);
    }
  } catch (const RecordingDamage& e) {
    // NOTE: every message given lies before the damage, and was checked there (its chunk's
    // CRC or index); the index says how many frames the damage took, when it is not lost.
    const RecordingIndex counted = ext == ".bag" ? index_rosbag(bytes) : index_mcap(bytes);
    const std::size_t listed = listing.listed;
    if (!options.salvage || listed == 0) {
      throw FormatError(damage_line(e, options.topic, listed, listing.last_stamp, counted));
    }
    RecordingSalvage salvage{e.what(), e.offset(), listed, std::nullopt};
    if (const auto total = counted.find(options.topic);
        total != counted.end() && total->second >= listed) {
      salvage.dropped = total->second - listed;
    }
    return salvage;
  }
  return std::nullopt;
}

/// Refuses a recording without a frame on the topic, naming the topics it has.
void require_frames(const Listing& listing) {
  if (!listing.frames.empty()) return;
  std::string names;
  for (const auto& [topic, type] : listing.topics) {
    names += cat(names.empty() ? "" : ", ", printable(topic, 60), " (", printable(type, 60), ")");
  }
  throw FormatError(cat("no message on topic ", printable(listing.options.topic, 60),
                        " (its topics: ", names.empty() ? "none" : names, ")"));
}

/// The depth images' points, each by the last camera info at or before it (else the first).
void points_of_images(Listing& listing) {
  const RecordingOptions& options = listing.options;
  std::vector<RosDepthImage>& images = listing.images;
  const std::vector<RosCameraInfo>& infos = listing.infos;
  if (images.empty()) return;
  if (infos.empty()) {
    throw FormatError(cat("no sensor_msgs/CameraInfo on ", printable(listing.info_topic, 60),
                          " for the depth images of ", printable(options.topic, 60)));
  }
  for (std::size_t i = 0; i < images.size(); ++i) {
    const RosCameraInfo* info = &infos.front();
    for (const RosCameraInfo& c : infos) {
      if (c.header.stamp <= images[i].header.stamp) info = &c;
    }
    try {
      listing.frames[i].points = depth_to_points(images[i].image, info->intrinsics, options.depth);
    } catch (const std::invalid_argument& e) {
      throw FormatError(cat("image ", i + 1, " of ", printable(options.topic, 60), ": ", e.what()));
    }
    images[i].image.depth = {};
  }
}

// NOTE: a fixed frame tf never names would leave every frame unposed, and the frames placed by
// the table and registration instead, without a word (issue 53).
void check_fixed_frame(const Listing& listing) {
  const std::string& fixed_frame = listing.options.fixed_frame;
  if (fixed_frame.empty()) return;
  const std::set<std::string> known = listing.tf.frames();
  const bool own = std::any_of(listing.frames.begin(), listing.frames.end(),
                               [&](const RecordingFrame& f) { return f.frame_id == fixed_frame; });
  if (own || known.contains(fixed_frame)) return;
  std::string names;
  for (const std::string& name : known) {
    if (names.size() > 300) {
      names += ", ...";
      break;
    }
    names += cat(names.empty() ? "" : ", ", printable(name, 60));
  }
  throw FormatError(cat("fixed_frame ", printable(fixed_frame, 60), " is no frame of its tf (",
                        known.empty() ? std::string("it holds no tf on /tf or /tf_static")
                                      : cat("its frames: ", names),
                        ")"));
}

}  // namespace

Recording read_recording(const std::filesystem::path& path, const RecordingOptions& options) {
  check_options(options);
  const std::string where = path.string();
  try {
    const std::string ext = lower_extension(path);
    const std::string bytes = read_whole(path, ext);
    Listing listing(options);
    std::optional<RecordingSalvage> salvage = list_messages(bytes, ext, listing);
    require_frames(listing);
    points_of_images(listing);
    listing.tf.finish();
    check_fixed_frame(listing);
    std::vector<RecordingFrame>& frames = listing.frames;
    const std::string fixed = options.fixed_frame.empty() ? listing.tf.root(frames.front().frame_id)
                                                          : options.fixed_frame;
    for (RecordingFrame& frame : frames) {
      frame.T_fixed_cloud =
          listing.tf.lookup(frame.frame_id, fixed, frame.stamp, options.max_time_difference);
    }
    std::optional<PinholeIntrinsics> intrinsics;
    if (!listing.infos.empty()) intrinsics = listing.infos.front().intrinsics;
    return {std::move(frames), std::move(salvage), intrinsics};
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(cat(where, ": ", e.what()));
  }
}

}  // namespace vantage
