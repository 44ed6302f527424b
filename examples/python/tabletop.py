#!/usr/bin/env python3
"""Next-best-view planning on a simulated table top, from Python: a notebook-style tour of the
bindings. Each `# %%` cell runs on its own in Jupyter or VS Code; as a script it runs them all in
a few seconds.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/tabletop.py [OUT_DIR]

OUT_DIR (default: a fresh temporary folder) receives map.bt (open it with octovis) and
tabletop.png.
"""

# %% Set-up: the package, and a folder for what we write.
import pathlib
import sys
import tempfile

import numpy as np

import vantage as vt

out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(tempfile.mkdtemp())
out.mkdir(parents=True, exist_ok=True)

# %% The paper's ray model on MODEL.md's worked example: a sensor's ray crosses two free cells,
# two unobserved ones, an occupied one and one more unobserved. Visibility falls behind the
# occupied cell, and so does the information the sensor can expect to gain there.
trace = vt.RayModel(alpha=vt.TABLE_TOP_ALPHA).trace([0.12, 0.12, 0.5, 0.5, 0.97, 0.5])
print("cell  occupancy  visibility  posterior  gain [bits]")
for m, (p, v, q, g) in enumerate(zip(trace.occupancy, trace.visibility, trace.posterior,
                                     trace.gain)):
    print(f"{m:4d}  {p:9.2f}  {v:10.4f}  {q:9.4f}  {g:11.4f}")

# %% A built-in scene: a table with objects, the PR2's tilting laser, and 30 candidate views on
# a ring around the table (10 positions x 3 yaw offsets).
world = vt.World("tabletop-1")
scene = world.scene
candidates = scene.candidate_poses()  # K x 4 x 4 sensor poses (x forward, y left, z up)
print(f"\n{scene}: grid {scene.grid}, {len(candidates)} candidate views")

# %% The first scan, from the scene's start pose: an N x 3 array in the sensor frame. The mapper
# keeps the points above the table and integrates them as the paper does (hits, hole filling,
# unknown-space estimation).
mapper = vt.Mapper(scene.grid, table_segmentation=True)
pose = scene.start_poses[0]
points = world.scan(pose, seed=1)
update = mapper.add_scan(points, pose, scene.fov)
print(f"scan 1: {len(points)} points, {update.object_points} on the objects, "
      f"{update.integration.left_unobserved} cells seen")

# %% Next best views: score every candidate by its expected information gain (eq. 1), choose
# the best, scan from there, repeat. The prediction is in bits; what the scan then reveals is in
# cells, so the two differ in scale but should rise and fall together.
for step in range(2, 4):
    grid = mapper.grid
    plan = vt.plan_next_view(grid, candidates, scene.fov)
    print(f"\ndecision {step - 1} ({plan.seconds * 1e3:.0f} ms): top candidates")
    for i in plan.ranking[:3]:
        print(f"  view {i:2d} at {np.round(candidates[i][:3, 3], 2)}: "
              f"{plan.gains[i].gain:7.1f} bits over {plan.gains[i].targets} unobserved cells")
    pose = candidates[plan.best]
    update = mapper.add_scan(world.scan(pose, seed=step), pose, scene.fov)
    print(f"scan {step} from view {plan.best}: {update.integration.left_unobserved} cells seen")

# %% The map as numpy arrays shaped like the grid, indexed [i, j, k].
grid = mapper.grid
states = grid.states()
print(f"\nmap {grid.shape}: {grid.counts()}")
occupied = np.argwhere(states == vt.OCCUPIED)
centres = grid.spec.origin + (occupied + 0.5) * grid.spec.resolution
print(f"objects span x {centres[:, 0].min():.2f}..{centres[:, 0].max():.2f} m, "
      f"z up to {centres[:, 2].max():.2f} m")

# %% Save the map for OctoMap's tools, and read it back.
grid.save(out / "map.bt")
again = vt.OccupancyGrid.load(out / "map.bt", spec=grid.spec)
assert np.array_equal(again.states(), states)

# %% A picture: the occupied cells seen from above, and at each ring position the predicted gain
# on the final map (the best of its three yaw offsets).
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

gains = np.array([g.gain for g in vt.evaluate_views(grid, candidates, scene.fov)])
per_position = gains.reshape(-1, 3).max(axis=1)
fig, ax = plt.subplots(figsize=(6, 5))
lo, hi = grid.spec.origin, grid.spec.max_corner
ax.imshow((states == vt.OCCUPIED).any(axis=2).T, origin="lower", cmap="Greys",
          extent=(lo[0], hi[0], lo[1], hi[1]))
xy = candidates[::3, :2, 3]
dots = ax.scatter(xy[:, 0], xy[:, 1], c=per_position, cmap="viridis")
fig.colorbar(dots, label="predicted gain [bits]")
ax.set(xlabel="x [m]", ylabel="y [m]", title=f"{scene.name}: map after 3 scans")
ax.set_aspect("equal")
fig.savefig(out / "tabletop.png", dpi=80)
print(f"\nwrote {out / 'map.bt'} and {out / 'tabletop.png'}")
