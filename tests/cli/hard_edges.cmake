# issue 39: the classes still open after issue 27. Every input file is opened one way (a regular
# file of at most its kind's size, its format sniffed where an extension can lie); work is sized
# before it starts; values are refused where they are read, against one table of limits
# (vantage/util/limits.hpp); outputs are checked before the work. Included from CMakeLists.txt.
set(hard ${data}/hard_edges)
file(MAKE_DIRECTORY ${hard})

# A manifest that maps a few points in front of the sensor: what a run reads before its
# candidates.
file(WRITE ${hard}/front.pcd "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n1 0 0\n1.1 0.1 0\n1.2 0 0.1\n")
file(WRITE ${hard}/front.yaml "clouds: [{file: front.pcd, pose: ${identity}}]\n${sensor}\nroi: {min: [0.5, -0.5, -0.5], max: [1.5, 0.5, 0.5]}\nresolution: 0.05\noptions: {table_segmentation: false, icp: false}\n")

# 1. Not a regular file: a candidates file that is a FIFO waited forever, one linked to /dev/zero
# grew past 4 GiB.
file(REMOVE ${hard}/fifo.txt ${hard}/zero.txt)
execute_process(COMMAND mkfifo ${hard}/fifo.txt)
file(CREATE_LINK /dev/zero ${hard}/zero.txt SYMBOLIC)
# Refused before the manifest is read (the manifest here does not exist), not after the mapping.
add_test(NAME cli.plan_candidates_fifo
         COMMAND ${expect} --code 1 --absent ${hard}/out_fifo "--candidates ${hard}/fifo.txt: is a FIFO, not a regular file"
                 $<TARGET_FILE:vantage> plan ${hard}/missing.yaml --candidates ${hard}/fifo.txt --no-plots
                 --out ${hard}/out_fifo)
add_test(NAME cli.plan_candidates_dev_zero
         COMMAND ${expect} --code 1 --absent ${hard}/out_zero "zero.txt: is a character device, not a regular file"
                 $<TARGET_FILE:vantage> plan ${hard}/missing.yaml --candidates ${hard}/zero.txt --no-plots
                 --out ${hard}/out_zero)

# 2. Work sized before it starts.
file(READ ${PROJECT_SOURCE_DIR}/scenes/tabletop-1.yaml tabletop_one)
string(REPEAT "0 1 0 1 0 0 0 1\n" 100001 many_poses)
file(WRITE ${hard}/many_poses.txt "${many_poses}")
add_test(NAME cli.plan_candidates_too_many
         COMMAND ${expect} --code 1 --absent ${hard}/out_many "more than 100000 poses, the most a pose file may hold"
                 $<TARGET_FILE:vantage> plan ${hard}/front.yaml --candidates ${hard}/many_poses.txt --no-plots
                 --out ${hard}/out_many)
vantage_cli_usage(plan_views_too_many "--views 1000000 makes 3000000 candidate views, more than the 100000"
                  plan --map ${hard}/missing.ot --views 1000000)
vantage_cli_usage(explore_view_spacing_tiny "hemisphere.spacing (--view-spacing) 1e-09 m makes about"
                  explore --candidates hemisphere --view-spacing 1e-9 --scans 1)
string(REPLACE "objects:\n" "objects:\n  - {type: sphere, radius: 0.01, pose: [0, 0, 0.8], repeat: {count: [1000, 1000], step: [0.001, 0.001]}}\n"
       many_spheres "${tabletop_one}")
file(WRITE ${hard}/many_spheres.yaml "${many_spheres}")
vantage_cli_failure(scene_objects_too_many "places 1000000 copies, which makes more than the 10000 objects"
                    scene ${hard}/many_spheres.yaml)
file(READ ${PROJECT_SOURCE_DIR}/scenes/office-large-sparse.yaml office_sparse)
string(REPLACE "stop_spacing: 0.5" "stop_spacing: 0.1" many_stops "${office_sparse}")
file(WRITE ${hard}/many_stops.yaml "${many_stops}")
vantage_cli_failure(scene_stops_too_many "makes 50000 stops, more than the 20000 the ground truth sweeps from"
                    scene ${hard}/many_stops.yaml)

# 2b. A decision's work and memory estimated before it is computed, against --max-work and
# --max-memory (docs/robustness.md, "Work"). A narrow sensor over a grid of 80^3 cells: 99 999
# ring views cost at least 72 s whatever the map (each view's rays set up and walked), refused
# before the clouds are mapped (the swept search took 17-22 s for 30 000 views of a wider sensor
# on such a grid left unobserved).
file(WRITE ${hard}/narrow.yaml "clouds: [{file: front.pcd, pose: ${identity}}]\nsensor: {frame: x_forward, fov_deg: {horizontal: 10, vertical: 10}, min_range: 0.1, max_range: 3.0}\nroi: {min: [0.5, -0.5, -0.5], max: [1.5, 0.5, 0.5]}\nresolution: 0.0125\noptions: {table_segmentation: false, icp: false}\n")
add_test(NAME cli.plan_ring_work_budget
         COMMAND ${expect} --code 2 --absent ${hard}/out_ring "more than --max-work 60 s allows: raise it"
                 $<TARGET_FILE:vantage> plan ${hard}/narrow.yaml --candidates ring --views 33333 --no-plots
                 --out ${hard}/out_ring)
# issue 39: --method sequence --views 100000 --shortlist 1000000 said "out of memory" after 108 s:
# its travel table alone is 80 GB, refused before the clouds are mapped.
add_test(NAME cli.plan_sequence_shortlist_memory
         COMMAND ${expect} --code 2 --absent ${hard}/out_seq "more than --max-memory 4 GiB: decide among fewer views (or a smaller shortlist"
                 $<TARGET_FILE:vantage> plan ${hard}/front.yaml --method sequence --views 33333
                 --shortlist 1000000 --max-memory 4G --no-plots --out ${hard}/out_seq)
# The least the decision can cost, whatever the map, is weighed before the clouds are mapped.
vantage_cli_usage(plan_max_work_tiny "the swept search over 30 views, about 7107 grid cells in each view's frustum, is estimated at 0.0401 s"
                  plan ${hard}/front.yaml --max-work 0.001 --no-plots --out ${hard}/out_work)
vantage_cli_usage(plan_max_work_zero "--max-work: " plan ${hard}/front.yaml --max-work 0)
# explore and bench: a sequence's shortlist up front (13 164 hemisphere views: a travel table of
# 1.4 GB), before the world is built; each decision on its map as the run goes (the paper's method
# after the first scan: its pruned search at worst evaluates every view).
vantage_cli_usage(explore_sequence_shortlist_memory "more than --max-memory 1 GiB: decide among fewer views (or a smaller shortlist"
                  explore --method sequence --candidates hemisphere --view-spacing 0.003 --shortlist 100000
                  --max-memory 1G --scans 2 --out ${hard}/out_explore_seq)
vantage_cli_usage(bench_sequence_shortlist_memory "more than --max-memory 1 GiB: decide among fewer views (or a smaller shortlist"
                  bench tabletop --scenes tabletop-1 --methods sequence --candidates hemisphere --view-spacing 0.003
                  --shortlist 100000 --max-memory 1G --trials 1 --scans 2 --out ${hard}/out_bench_seq)
# The yardstick's scans of 13 164 hemisphere views, refused before the world is built (they ran
# for minutes before the first decision's check).
add_test(NAME cli.explore_yardstick_budget
         COMMAND ${expect} --code 2 --absent ${hard}/out_explore_truth
                 "the surface yardstick's noise-free scans of 13164 candidate views"
                 $<TARGET_FILE:vantage> explore --scene tabletop-4 --candidates hemisphere
                 --view-spacing 0.003 --scans 1 --no-plots --quiet --out ${hard}/out_explore_truth)
add_test(NAME cli.explore_work_budget
         COMMAND ${expect} --code 2 --absent ${hard}/out_explore_work "the pruned search over 29 views"
                 $<TARGET_FILE:vantage> explore --method probabilistic --max-work 1 --scans 2 --no-plots --quiet
                 --out ${hard}/out_explore_work)

# 3. Values accepted that should not be.
vantage_cli_usage(ray_cells_hex "--cells: '0x1p-3' (item 0) is not a number" ray --cells 0x1p-3)
file(WRITE ${hard}/res_twice.bt "# Octomap OcTree binary file\nid OcTree\nsize 0\nres 0.1\nres 10\ndata\n")
vantage_cli_failure(plan_octomap_res_twice "res_twice.bt: header: 'res' is given twice"
                    plan --map ${hard}/res_twice.bt)
string(REPLACE "objects:\n" "objects:\n  - {type: sphere, radius: 1e10, pose: [0, 0, 0.8]}\n" huge_sphere "${tabletop_one}")
file(WRITE ${hard}/huge_sphere.yaml "${huge_sphere}")
vantage_cli_failure(scene_sphere_radius_huge "radius: must be at most 100000 m, got 1e+10"
                    scene ${hard}/huge_sphere.yaml)
file(WRITE ${hard}/m.xyz "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
file(WRITE ${hard}/m.off "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
string(REPLACE "objects:\n" "objects:\n  - {type: mesh, file: m.xyz, scale: 0.1, pose: [0, 0, 0.8]}\n" xyz_mesh "${tabletop_one}")
file(WRITE ${hard}/xyz_mesh.yaml "${xyz_mesh}")
string(REPLACE "objects:\n" "objects:\n  - {type: mesh, file: m.off, scale: 0.1, pose: [0, 0, 0.8]}\n" off_mesh "${tabletop_one}")
file(WRITE ${hard}/off_mesh.yaml "${off_mesh}")
vantage_cli_failure(scene_mesh_extension_unknown "'.xyz' is not a mesh format vantage reads"
                    scene ${hard}/xyz_mesh.yaml)
vantage_cli_failure(scene_mesh_content_lies "m.off holds OBJ text, not what its .off extension says"
                    scene ${hard}/off_mesh.yaml)
file(READ ${PROJECT_SOURCE_DIR}/scenes/office-small-sparse.yaml office_small)
string(REPLACE "stop_spacing: 0.5" "stop_spacing: 0.000001" tiny_stops "${office_small}")
file(WRITE ${hard}/tiny_stops.yaml "${tiny_stops}")
vantage_cli_failure(scene_stop_spacing_tiny "stop_spacing: must be at least the grid's resolution (0.04 m), got 1e-06"
                    scene ${hard}/tiny_stops.yaml)
file(MAKE_DIRECTORY ${hard}/pl)
file(WRITE ${hard}/pl/plan.json "{}\n")
vantage_cli_failure(view_out_is_input "--out ${hard}/pl/plan.json is an input of this run"
                    view ${hard}/pl --out ${hard}/pl/plan.json)
add_test(NAME cli.view_out_no_folder
         COMMAND ${expect} --code 1 --absent ${hard}/no "${hard}/no/such does not exist"
                 $<TARGET_FILE:vantage> view ${hard}/pl --out ${hard}/no/such/v.html)

# 4. Messages that point the right way.
vantage_cli_failure(plan_cloud_as_manifest "front.pcd: is a PCD point cloud, not a manifest"
                    plan ${hard}/front.pcd)
vantage_cli_failure(plan_max_memory_tiny "more than --max-memory 1 KiB"
                    plan ${hard}/front.yaml --max-memory 1K --no-plots --out ${hard}/out_tiny)
vantage_cli_failure(bench_merge_missing_folder "bench merge: ${hard}/nope: no such folder"
                    bench merge ${hard}/pl ${hard}/nope)
vantage_cli_failure(explore_arm_reaches_nothing "set --arm-base and --reach"
                    explore --candidates hemisphere --arm-base 10,0,0.75 --reach 0.5 --scans 1
                    --out ${hard}/out_arm)

# 5. Exit codes: a malformed value is decided before any file is read (exit 2).
vantage_cli_usage(scan_out_format "--out: ${hard}/o.xyz: unsupported point-cloud format '.xyz'"
                  scan --scene tabletop-1 --view 0 --out ${hard}/o.xyz)
vantage_cli_usage(scan_out_no_extension "unsupported point-cloud format ''"
                  scan --scene tabletop-1 --view 0 --out ${hard}/o)
vantage_cli_usage(plan_map_format "--map: " plan --map ${hard}/m.txt)
# A picture's format is its extension's, decided before the scene's or the ray's work (the plot
# script failed after it, or wrote d.png for `--out d`).
vantage_cli_usage(scene_out_picture_format "--out ${hard}/d.txt: '.txt' is not a picture format"
                  scene tabletop-1 --out ${hard}/d.txt)
vantage_cli_usage(ray_plot_picture_format "--plot ${hard}/r: '' is not a picture format"
                  ray --scenario 4 --plot ${hard}/r)
# scan --out into a missing folder is refused before the scan, as every output is.
add_test(NAME cli.scan_out_no_folder
         COMMAND ${expect} --code 1 --absent ${hard}/none "--out ${hard}/none/o.pcd: ${hard}/none does not exist"
                 $<TARGET_FILE:vantage> scan --scene tabletop-1 --view 0 --out ${hard}/none/o.pcd)
