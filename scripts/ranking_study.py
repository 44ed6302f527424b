#!/usr/bin/python3
"""How often the survival reading (a = 0.995, expected cells seen) and greedy's count choose the same
view, and how alike their rankings of the 30 ring views are, on the built-in table tops after 1, 3
and 6 scans (the two scan orders the screen's oracle test walks, mapped with table segmentation).
RESULTS.md, "The final sweep". Usage: PYTHONPATH=build/release/python scripts/ranking_study.py"""
import numpy as np, vantage as vt
orders = [[0, 5, 2, 7, 3, 8], [4, 9, 1, 6, 8, 3]]
same = total = 0
rho = []
for name in ["tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"]:
    world = vt.World(name); scene = world.scene
    for order in orders:
        mapper = vt.Mapper(scene.grid, table_segmentation=True)
        for k, start in enumerate(order):
            pose = scene.start_poses[start]
            mapper.add_scan(world.scan(pose), pose, scene.fov)
            if k not in (0, 2, 5): continue
            cands = scene.candidate_poses()
            plans = {}
            for m in ("greedy", "survival"):
                c = vt.PlannerConfig(method=m, gain=vt.GainConfig(alpha=0.995, evaluation="exact"))
                plans[m] = vt.plan_next_view(mapper.grid, cands, scene.fov, c)
            g = np.array([x.cells for x in plans["greedy"].gains]); s = np.array([x.cells for x in plans["survival"].gains])
            rg = np.argsort(np.argsort(-g)); rs = np.argsort(np.argsort(-s))
            rho.append(np.corrcoef(rg, rs)[0, 1])
            bg, bs = int(np.argmax(g)), int(np.argmax(s))
            total += 1; same += bg == bs
            print(name, k + 1, bg, bs, round(rho[-1], 3), flush=True)
print(f"same choice in {same} of {total} states; Spearman rank correlation median {np.median(rho):.3f}, min {min(rho):.3f}")
