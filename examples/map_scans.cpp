// Maps a robot's recorded clouds with vantage::Mapper — the paper's pipeline: ICP registration
// (when the manifest asks for it), table segmentation, integration into the occupancy grid — and
// plans the next view, with an installed Vantage. Then saves the map losslessly, as a robot would
// between two steps of its loop.
//
// Usage: map_scans DATA_DIR    (a folder with manifest.yaml and its clouds, e.g. the one
//                               examples/own-scans/make-data.sh writes; see docs/manifest.md)
#include <cstdio>
#include <exception>
#include <vantage/experiment/recorded.hpp>
#include <vantage/io/octomap_io.hpp>
#include <vantage/perception/mapper.hpp>
#include <vantage/planner/planner.hpp>
#include <vantage/views/ring.hpp>

using namespace vantage;

int main(int argc, char** argv) try {
  if (argc != 2) {
    std::fprintf(stderr, "usage: map_scans DATA_DIR\n");
    return 2;
  }
  const Manifest manifest = read_manifest(argv[1]);

  // Every cloud of the manifest, read from disk and added with Mapper::add_scan at its pose.
  Mapper mapper(manifest.grid, mapper_config_for(manifest));
  map_recorded(manifest, mapper, [&](const RecordedCloud& cloud) {
    std::printf("cloud %zu: %zu points, %zu above the table integrated\n", cloud.index + 1,
                cloud.update.points, cloud.update.object_points);
  });
  const CellCounts counts = mapper.grid().counts();
  std::printf("map: %zu unobserved, %zu free, %zu occupied cells\n", counts.unobserved, counts.free,
              counts.occupied);

  // 10 places on a ring around the region of interest, 3 yaws each, 0.3 m above it.
  RingConfig ring;
  ring.center = manifest.roi.center();
  ring.radius = 1.1;
  ring.height = manifest.roi.max().z() + 0.3;
  std::vector<Candidate> candidates;
  for (const Frustum& view : make_views(ring_poses(ring), manifest.fov)) {
    candidates.push_back({view});
  }
  const Plan plan = plan_next_view(mapper.grid(), candidates, PlannerConfig{});
  const Eigen::Vector3d at = candidates[plan.best].view.origin();
  std::printf("next best view %zu of %zu at (%.3f, %.3f, %.3f) m: predicted gain %.1f bits\n",
              plan.best, candidates.size(), at.x(), at.y(), at.z(), plan.gains[plan.best].gain);

  // map.ot keeps every cell's log-odds: read_octomap + Mapper(grid, config) continue from it
  // exactly as if every cloud were mapped again.
  write_octomap("map.ot", mapper.grid());
  std::printf("wrote map.ot\n");
} catch (const std::exception& e) {
  std::fprintf(stderr, "map_scans: %s\n", e.what());
  return 1;
}
