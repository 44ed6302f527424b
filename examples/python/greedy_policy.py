#!/usr/bin/env python3
"""A planner of your own in Vantage's loop: simple greedy (docs/model.md, "Baselines")
re-implemented in numpy on ExploreEnv's observation, then benched beside the built-in methods.

Greedy's gain of a view is the number of unobserved cells whose centre lies in the view's
frustum with no occupied cell on the ray from the sensor to it; the policy takes the untaken
candidate of the largest gain (ties to the lower index). Each ray's cells are found at once, from
its crossings of the grid's planes, rather than walked cell by cell as the library does; the
counts are the library's exact ones (to a cell where a ray runs through a cell's edge) and the
choices the built-in greedy's on the states python/tests/test_env.py tries; the built-in decides
with its swept search, which may take another view near the best. It is plain numpy: 4-7 s a
candidate at the first decision on tabletop-1's 129 x 129 x 65 grid, less later, so try it on
the ring or a coarse scene.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/greedy_policy.py [OUT_DIR]

runs one episode of tabletop-1's ring against the built-in greedy's choices, then benches the
policy and a random one on two starts into OUT_DIR (default: a fresh temporary folder); compare
them with the built-in methods by benching those into the same folder and plotting it:

    build/release/apps/vantage/vantage bench tabletop --scenes tabletop-1 --trials 2 \\
        --methods greedy,random --out OUT_DIR
    /usr/bin/python3 scripts/plot_bench.py OUT_DIR     # OUT_DIR/summary.md
"""

import pathlib
import sys
import tempfile

import numpy as np

import vantage as vt


def frustum_mask(points, T_world_sensor, fov):
    """Which world points (N x 3) lie in the sensor's frustum (Frustum::contains)."""
    R, o = T_world_sensor[:3, :3], T_world_sensor[:3, 3]
    p = (points - o) @ R  # in the sensor frame: x forward, y left, z up
    x, y, z = p[:, 0], p[:, 1], p[:, 2]
    r2 = np.einsum("ij,ij->i", p, p)
    return ((x > 0) & (r2 >= fov.min_range ** 2) & (r2 <= fov.max_range ** 2)
            & (np.abs(y) <= x * np.tan(fov.h_fov / 2)) & (np.abs(z) <= x * np.tan(fov.v_fov / 2)))


def crossed_cells(o, ends, origin, res, dims):
    """The cells each segment from `o` to a point of `ends` (T x 3) crosses, exactly: the cell of
    the midpoint of each stretch between two of its crossings of the grid's planes. Returns
    (i, j, k) index arrays of shape T x M and a mask of the stretches that exist and lie in the
    grid (cells outside it are free)."""
    d = ends - o
    ts = [np.zeros((len(d), 1)), np.ones((len(d), 1))]
    with np.errstate(divide="ignore", invalid="ignore"):
        for a in range(3):
            t = (origin[a] + res * np.arange(dims[a] + 1) - o[a])[None, :] / d[:, a:a + 1]
            t[~((t > 0) & (t < 1))] = np.nan  # NaN sorts last
            ts.append(t)
    t = np.sort(np.concatenate(ts, axis=1), axis=1)
    mid = (t[:, :-1] + t[:, 1:]) / 2
    ijk = np.floor((o + np.nan_to_num(mid)[..., None] * d[:, None, :] - origin) / res)
    ijk = ijk.astype(np.int64)
    inside = ~np.isnan(mid) & np.all((ijk >= 0) & (ijk < dims), axis=2)
    ijk[~inside] = 0
    return ijk[..., 0], ijk[..., 1], ijk[..., 2], inside


def greedy_gains(obs, grid, fov, chunk=2048):
    """Greedy's gain [cells] of every candidate (NaN where taken): the unobserved cells in view
    that no occupied cell hides, each on its own ray from the sensor to its centre."""
    cells = obs["cells"]
    res, origin, dims = grid.resolution, np.asarray(grid.origin), np.asarray(grid.dims)
    occupied = cells == vt.OCCUPIED
    centres = origin + (np.argwhere(cells == vt.UNOBSERVED) + 0.5) * res
    gains = np.full(len(obs["candidates"]), np.nan)
    for k, pose in enumerate(obs["candidates"]):
        if obs["taken"][k]:
            continue
        seen = centres[frustum_mask(centres, pose, fov)]
        count = 0
        for start in range(0, len(seen), chunk):
            i, j, l, inside = crossed_cells(pose[:3, 3], seen[start:start + chunk], origin, res,
                                            dims)
            # NOTE: the target's own cell is unobserved, so the last stretch never blocks.
            count += int((~(occupied[i, j, l] & inside).any(axis=1)).sum())
        gains[k] = count
    return gains


def greedy_policy(grid, fov):
    """The policy: the untaken candidate of the largest greedy gain, ties to the lower index."""

    def policy(obs):
        return int(np.nanargmax(greedy_gains(obs, grid, fov)))

    policy.__name__ = "numpy-greedy"
    return policy


if __name__ == "__main__":
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(tempfile.mkdtemp())
    env = vt.ExploreEnv("tabletop-1", candidates="ring", scans=4, seed=1, reference="greedy")
    policy = greedy_policy(env.grid, env.fov)
    obs, info = env.reset()
    done = False
    while not done:
        view = policy(obs)
        print(f"scan {obs['scan'] + 1}: numpy greedy takes view {view}, the built-in greedy "
              f"{info['reference']['view']}")
        obs, reward, done, _, info = env.step(view)
        print(f"  surface coverage {info['surface_coverage']:.3f} (+{reward:.3f})")
    for p in (policy, vt.random_policy(seed=0)):
        ran = vt.bench_policy(p, ["tabletop-1"], trials=2, scans=4, out=out)
        print(f"{p.__name__}: {ran} trial(s) into {out / 'scans.csv'}")
