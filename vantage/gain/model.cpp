#include "vantage/gain/model.hpp"

#include <algorithm>

#include "vantage/gain/ray_model.hpp"

namespace vantage {

std::vector<RayOdds> PaperModel::uniform_run(double alpha, double p, int n) {
  const UniformPrefix prefix(RayModel(alpha), p, n);
  std::vector<RayOdds> run;
  run.reserve(static_cast<std::size_t>(std::max(n, 0)));
  for (int k = 1; k <= n; ++k) run.emplace_back(prefix.at(k).visibility, prefix.at(k).posterior);
  return run;
}

std::vector<RayOdds> BlindModel::uniform_run(double alpha, double p, int n) {
  std::vector<RayOdds> run;
  if (n < 1) return run;
  run.push_back(start(p));
  double t = 1.0;
  for (int k = 2; k <= n; ++k) {
    t *= alpha;
    RayOdds s = run.back();
    step(s, t, p, p);
    run.push_back(s);
  }
  return run;
}

}  // namespace vantage
