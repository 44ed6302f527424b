#include "vantage/io/tum_rgbd.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/trajectory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

std::vector<TumFrame> read_tum_rgbd(const fs::path& folder, const TumReadOptions& options) {
  if (options.every < 1) {
    throw std::invalid_argument(cat("every must be >= 1, got ", options.every));
  }
  if (!(options.max_time_difference > 0.0)) {
    throw std::invalid_argument(
        cat("max_time_difference must be positive, got ", options.max_time_difference));
  }
  const fs::path list = folder / "depth.txt";
  std::string text;
  try {
    text = read_input_file(list, InputKind::kPoses);
  } catch (const FormatError& e) {
    throw std::runtime_error(cat(list.string(), ": ", e.what(),
                                 " (a TUM RGB-D folder lists its depth frames in depth.txt)"));
  }
  std::optional<std::vector<StampedPose>> truth;
  if (std::error_code error; fs::exists(folder / "groundtruth.txt", error)) {
    truth = read_tum_trajectory(folder / "groundtruth.txt");
  }
  std::vector<TumFrame> frames;
  Lines lines(text);
  std::size_t listed = 0;
  double last_stamp = -INFINITY;
  while (const auto line = lines.next()) {
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(cat(list.string(), ":", lines.number(), ": ", what));
    };
    const std::vector<std::string_view> tokens = split(*line);
    if (tokens.empty() || tokens.front().starts_with('#')) continue;
    if (tokens.size() != 2) {
      fail(cat(tokens.size(), " fields; a depth frame has 2 (timestamp filename)"));
    }
    const std::optional<double> stamp = parse_number(tokens[0]);
    if (!stamp || !std::isfinite(*stamp)) {
      fail(cat("timestamp '", printable(tokens[0], 40), "' is not a finite number"));
    }
    if (!(*stamp > last_stamp)) {
      fail(cat("time stamps must increase (", *stamp, " s follows ", last_stamp, " s)"));
    }
    last_stamp = *stamp;
    if (listed++ % static_cast<std::size_t>(options.every) != 0) continue;
    TumFrame frame;
    frame.file = (folder / std::string(tokens[1])).lexically_normal();
    frame.stamp = *stamp;
    if (const std::string why = input_file_problem(frame.file, InputKind::kDepthImage);
        !why.empty()) {
      fail(cat(frame.file.string(), ": ", why));
    }
    if (truth) {
      try {
        frame.T_world_cloud = interpolate_pose(*truth, *stamp, options.max_time_difference);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(cat((folder / "groundtruth.txt").string(), ": ", e.what()));
      }
    }
    frames.push_back(frame);
  }
  if (frames.empty()) throw std::runtime_error(cat(list.string(), ": lists no depth frame"));
  return frames;
}

}  // namespace vantage
