#!/usr/bin/python3
"""Writes the seed corpora of fuzz/corpus/<reader>/: tiny valid files and edge cases of each
format. The files are checked in; rerun after changing this script. Usage: fuzz/make_seeds.py"""
import os
import struct
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def lzf_literal(data):
    """LZF of `data` as literal runs only (up to 32 bytes a run), which any LZF decoder reads."""
    out = bytearray()
    for i in range(0, len(data), 32):
        chunk = data[i:i + 32]
        out.append(len(chunk) - 1)
        out += chunk
    return bytes(out)


def write(reader, name, data):
    folder = os.path.join(HERE, "corpus", reader)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def pcd_header(fields, size, type_, count, n, data, viewpoint="0 0 0 1 0 0 0"):
    return (f"# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\n"
            f"SIZE {size}\nTYPE {type_}\nCOUNT {count}\nWIDTH {n}\nHEIGHT 1\n"
            f"VIEWPOINT {viewpoint}\nPOINTS {n}\nDATA {data}\n")


def pcd_seeds():
    pts = [(0.1, 0.2, 1.0), (-0.5, 0.25, 2.0), (1.5, -1.0, 0.5)]
    write("pcd", "ascii.pcd", pcd_header("x y z", "4 4 4", "F F F", "1 1 1", 3, "ascii") +
          "".join(f"{x} {y} {z}\n" for x, y, z in pts))
    binary = b"".join(struct.pack("<3f", *p) for p in pts)
    write("pcd", "binary.pcd", pcd_header("x y z", "4 4 4", "F F F", "1 1 1", 3, "binary").encode() + binary)
    # binary_compressed: fields stored one after another (x x x y y y z z z), then LZF.
    soa = b"".join(struct.pack("<3f", *[p[a] for p in pts]) for a in range(3))
    packed = lzf_literal(soa)
    write("pcd", "compressed.pcd",
          pcd_header("x y z", "4 4 4", "F F F", "1 1 1", 3, "binary_compressed").encode() +
          struct.pack("<II", len(packed), len(soa)) + packed)
    # More fields, doubles, an rgb and a count of 2, an organized cloud with a NaN, a viewpoint.
    write("pcd", "fields.pcd",
          pcd_header("x y z rgb normal", "8 8 8 4 4", "F F F U F", "1 1 1 1 2", 2, "ascii",
                     "1 2 3 0.7071068 0 0.7071068 0") +
          "0 0 1 4278190335 0 1\n0.5 0.5 1.5 255 1 0\n")
    write("pcd", "organized_nan.pcd",
          "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 2\n"
          "POINTS 4\nDATA ascii\nnan nan nan\n0 0 1\n1 1 1\nnan nan nan\n")
    write("pcd", "ints.pcd", pcd_header("x y z", "2 2 2", "I I I", "1 1 1", 1, "binary").encode() +
          struct.pack("<3h", 1, -2, 3))
    write("pcd", "header_only.pcd", pcd_header("x y z", "4 4 4", "F F F", "1 1 1", 0, "ascii"))


def ply_seeds():
    pts = [(0.1, 0.2, 1.0), (-0.5, 0.25, 2.0), (1.5, -1.0, 0.5)]

    def header(fmt, extra=""):
        return (f"ply\nformat {fmt} 1.0\ncomment seed\nelement vertex 3\nproperty float x\n"
                f"property float y\nproperty float z\n{extra}end_header\n")
    write("ply", "ascii.ply", header("ascii") + "".join(f"{x} {y} {z}\n" for x, y, z in pts))
    write("ply", "le.ply", header("binary_little_endian").encode() +
          b"".join(struct.pack("<3f", *p) for p in pts))
    write("ply", "be.ply", header("binary_big_endian").encode() +
          b"".join(struct.pack(">3f", *p) for p in pts))
    # A mesh: colours, a face list with uchar counts and int indices, obj_info.
    write("ply", "mesh.ply",
          "ply\nformat ascii 1.0\nobj_info seed\nelement vertex 3\nproperty double x\n"
          "property double y\nproperty double z\nproperty uchar red\nelement face 1\n"
          "property list uchar int vertex_indices\nend_header\n"
          "0 0 0 255\n1 0 0 0\n0 1 0 9\n3 0 1 2\n")
    write("ply", "mesh_le.ply",
          b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float32 x\n"
          b"property float32 y\nproperty float32 z\nelement face 1\n"
          b"property list uint8 uint32 vertex_indices\nend_header\n" +
          struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3I", 3, 0, 1, 2))
    write("ply", "crlf.ply", header("ascii").replace("\n", "\r\n") + "1 2 3\r\n4 5 6\r\n7 8 9\r\n")


MANIFEST = """clouds:
  - file: a.pcd
    pose:
      - [0.0, 0.0, 1.0, -0.90]
      - [-1.0, 0.0, 0.0, 0.00]
      - [0.0, -1.0, 0.0, 0.75]
      - [0.0, 0.0, 0.0, 1.0]
  - file: a.ply
    pose: [-1, 0, 0, 0,  0, 0, -1, 0.9,  0, -1, 0, 0.75,  0, 0, 0, 1]
sensor:
  frame: optical
  intrinsics: {fx: 525.0, fy: 525.0, cx: 319.5, cy: 239.5, width: 640, height: 480}
  min_range: 0.3
  max_range: 3.5
roi:
  min: [-0.5, -0.5, 0.0]
  max: [0.5, 0.5, 0.5]
resolution: 0.0078125
options: {table_segmentation: false, icp: false, integration: paper, skip_non_finite: false}
"""


def manifest_seeds():
    # The harness puts a.pcd (with a VIEWPOINT), a.ply, 2.5.pcd and trajectory.txt beside the
    # manifest (fuzz/manifest_fuzzer.cpp).
    write("manifest", "poses.yaml", "version: 1\n" + MANIFEST)
    write("manifest", "fov_xforward.yaml",
          "clouds: [{file: a.pcd, stamp: 1.5}]\nsensor: {frame: x_forward, "
          "fov_deg: {horizontal: 90, vertical: 45}, min_range: 0.1, max_range: 3.0}\n"
          "roi: {min: [-0.5, -0.5, 0.75], max: [0.5, 0.5, 1.25]}\nresolution: 0.01\n"
          "options: {integration: endpoint}\n")
    write("manifest", "trajectory.yaml",
          "clouds: [{file: a.pcd, stamp: 1.0}, {file: 2.5.pcd}]\n"
          "trajectory: {file: trajectory.txt, match: timestamp, max_time_difference: 0.02}\n"
          "sensor: {frame: optical, fov_deg: {horizontal: 57, vertical: 43}, min_range: 0.3, "
          "max_range: 3.5}\nroi: {min: [-1, -1, 0], max: [1, 1, 1]}\nresolution: 0.05\n")
    write("manifest", "folder.yaml",
          "trajectory: {file: trajectory.txt}\nsensor: {frame: optical, fov_deg: "
          "{horizontal: 57, vertical: 43}, min_range: 0.3, max_range: 3.5}\n"
          "roi: {min: [-1, -1, 0], max: [1, 1, 1]}\nresolution: 0.05\n")
    write("manifest", "viewpoint.yaml",
          "clouds: [{file: a.pcd}]\nsensor: {frame: x_forward, fov_deg: {horizontal: 60, "
          "vertical: 45}, min_range: 0.1, max_range: 2}\nroi: {min: [0, 0, 0], max: [1, 1, 1]}\n"
          "resolution: 0.1\n")
    write("manifest", "anchors.yaml",
          "clouds: [{file: a.pcd}]\nsensor: {frame: optical, fov_deg: {horizontal: 60, "
          "vertical: 45}, min_range: &r 0.1, max_range: 2}\nroi: {min: [0, 0, 0], "
          "max: [1, 1, 1]}\nresolution: *r\n")
    write("manifest", "bad_pose.yaml", MANIFEST.replace("-0.90", ".nan"))
    # issue 39: a pose file, which the harness also reads as one (plan --candidates FILE).
    write("manifest", "poses.txt",
          "# timestamp tx ty tz qx qy qz qw\n0 1 0 1 0 0 0 1\n1 0 1 1 0 0 0.7071068 0.7071068\n"
          "\n2 -1 0 1.2 0 0 1 0\n")


def scene_seeds():
    scenes = os.path.join(HERE, "..", "scenes")
    for name in ("tabletop-1", "office-small-sparse"):
        with open(os.path.join(scenes, name + ".yaml"), "rb") as f:
            write("scene", name + ".yaml", f.read())
    write("scene", "minimal.yaml",
          "name: tiny\nkind: tabletop\ngrid: {origin: [0, 0, 0], resolution: 0.1, "
          "dims: [4, 4, 4]}\ntable: {size: [1, 1], height: 0.5}\nobjects:\n"
          "  - {type: box, size: [0.1, 0.1, 0.1], pose: [0, 0, 0.5, 0, 0, 0]}\n"
          "sensor: hokuyo\nmount: {height: 1.0, target: [0, 0, 0.5]}\n"
          "candidates: {generator: ring, radius: 1.0, positions: 3, yaw_offsets_deg: [0]}\n"
          "start_poses: ring\n")
    # issue 39: mesh references, to the files the harness puts beside the scene: the four
    # formats, then one seed for each file the mesh reader refuses.
    def meshes(names):
        return ("name: meshes\nkind: tabletop\ngrid: {origin: [0, 0, 0], resolution: 0.1, "
                "dims: [4, 4, 4]}\ntable: {size: [1, 1], height: 0.5}\nobjects:\n"
                + "".join(f"  - {{type: mesh, file: {name}, scale: 0.1, pose: [0, 0, 0.5]}}\n"
                          for name in names)
                + "sensor: hokuyo\nmount: {height: 1.0, target: [0, 0, 0.5]}\n"
                "candidates: {generator: ring, radius: 1.0, positions: 3, yaw_offsets_deg: [0]}\n"
                "start_poses: ring\n")
    write("scene", "mesh-files.yaml", meshes(["m.obj", "m.off", "m.ply", "m.stl"]))
    for name in ("lie.off", "m.xyz", "huge.off"):
        write("scene", f"mesh-{name.replace('.', '-')}.yaml", meshes([name]))


def bt_node(codes):
    """A `.bt` inner node: its 8 children's 2-bit codes (1 free leaf, 2 occupied leaf, 3 inner,
    0 unknown), child i in bits 2i and 2i+1."""
    bits = 0
    for i, code in enumerate(codes):
        bits |= code << (2 * i)
    return struct.pack("<H", bits)


def chain(child_at_root, leaves):
    """Inner nodes from the root down to depth 15, through child `child_at_root` of the root and
    child 0 below it, so that the leaves at depth 16 (OctoMap's finest voxels) lie at the origin
    (child 7 of the root, then child 0) or far from it."""
    first = [0] * 8
    first[child_at_root] = 3
    nodes = [first] + [[3, 0, 0, 0, 0, 0, 0, 0] for _ in range(14)] + [leaves]
    return nodes


def octomap_seeds():
    head = b"# Octomap OcTree binary file\n# comment\nid OcTree\nsize %d\nres 0.1\ndata\n"
    nodes = chain(7, [2, 0, 0, 0, 0, 0, 0, 1])  # one occupied and one free voxel at the origin
    write("octomap", "tiny.bt", head % (len(nodes) + 2) + b"".join(bt_node(n) for n in nodes))
    far = chain(0, [2, 2, 2, 2, 1, 1, 1, 1])
    write("octomap", "far.bt", head % (len(far) + 8) + b"".join(bt_node(n) for n in far))
    write("octomap", "coarse.bt", head % 3 + bt_node([2, 0, 0, 0, 0, 0, 0, 1]))
    write("octomap", "empty.bt", b"# Octomap OcTree binary file\nid OcTree\nsize 0\nres 0.05\ndata\n")

    # .ot: per node its float log-odds (a ColorOcTree adds r, g, b), then a byte with a bit per
    # existing child; children follow depth first.
    def ot(color):
        extra = b"\x01\x02\x03" if color else b""
        body = b""
        for depth in range(16):
            body += struct.pack("<f", 0.85) + extra + bytes([0x80 if depth == 0 else 0x01])
        body += struct.pack("<f", 0.85) + extra + b"\x00"  # occupied leaf
        tree = b"ColorOcTree" if color else b"OcTree"
        return (b"# Octomap OcTree file\nid " + tree + b"\nsize 17\nres 0.05\ndata\n" + body)
    write("octomap", "tiny.ot", ot(False))
    write("octomap", "color.ot", ot(True))


def png(width, height, bit_depth, colour, rows, interlace=0):
    """A PNG of raw `rows` (each with its filter byte), zlib'd into one IDAT."""
    import zlib

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(
            ">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour, 0, 0, interlace)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows)) +
            chunk(b"IEND", b""))


def depth_png_seeds():
    # 4 x 3 depths, 16-bit big-endian, each row with filter 0 (none), 1 (sub) or 2 (up).
    rows = b"".join(bytes([r % 3]) + struct.pack(">4H", 0, 5000 + r, 65535, 7) for r in range(3))
    write("depth_png", "tiny.png", png(4, 3, 16, 0, rows))
    write("depth_png", "interlaced.png", png(4, 3, 16, 0, rows, interlace=1))
    write("depth_png", "eight_bit.png", png(2, 1, 8, 0, b"\x00\x01\x02"))
    write("depth_png", "rgb.png", png(1, 1, 16, 2, b"\x00" + bytes(6)))


def tum_seeds():
    write("tum", "depth.txt", "# depth maps\n# timestamp filename\n1305031102.175304 depth/a.png\n"
          "1305031102.211214 depth/b.png\n")
    write("tum", "empty.txt", "# nothing\n")


def cloud_and_tf_ros1():
    """A 2-point PointCloud2 and a one-transform TFMessage in ROS 1 serialization."""
    def string(text):
        return struct.pack("<I", len(text)) + text.encode()
    header = struct.pack("<III", 0, 7, 500) + string("camera")
    fields = struct.pack("<I", 3) + b"".join(
        string(n) + struct.pack("<IBI", 4 * i, 7, 1) for i, n in enumerate("xyz"))
    data = struct.pack("<6f", 0.1, 0.2, 1.0, float("nan"), 0.0, 2.0)
    cloud = (header + struct.pack("<II", 1, 2) + fields + struct.pack("<BII", 0, 12, 24) +
             struct.pack("<I", len(data)) + data + b"\x01")
    tf = (struct.pack("<I", 1) + struct.pack("<III", 0, 7, 0) + string("world") + string("camera") +
          struct.pack("<7d", 1, 2, 3, 0, 0, 0, 1))
    return cloud, tf


def rosbag_seeds():
    """A tiny bag, written by Debian's python3-rosbag when it is there."""
    try:
        import rosbag
        import genpy
        from sensor_msgs.msg import PointCloud2
        from tf2_msgs.msg import TFMessage
    except ImportError:
        print("make_seeds: no python3-rosbag; the rosbag seeds are left as they are")
        return
    import tempfile
    cloud, tf = cloud_and_tf_ros1()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "tiny.bag")
        with rosbag.Bag(path, "w") as bag:
            t = genpy.Time(7, 500)
            bag.write("/tf", TFMessage().deserialize(tf), t)
            bag.write("/camera/depth/points", PointCloud2().deserialize(cloud), t)
        tiny = open(path, "rb").read()
        write("rosbag", "tiny.bag", tiny)
    rosbag_damaged_seeds(tiny)


def bag_records(b):
    """(offset, op, data offset, data size, header fields: value offset) of each top-level record."""
    out, pos = [], 13
    while pos < len(b):
        hl, = struct.unpack_from("<I", b, pos)
        fields, f = {}, pos + 4
        while f < pos + 4 + hl:
            n, = struct.unpack_from("<I", b, f)
            name = b[f + 4:f + 4 + n].split(b"=", 1)[0]
            fields[name] = f + 4 + len(name) + 1
            f += 4 + n
        dl, = struct.unpack_from("<I", b, pos + 4 + hl)
        out.append((pos, b[fields[b"op"]], pos + 8 + hl, dl, fields))
        pos += 8 + hl + dl
    return out


def rosbag_damaged_seeds(tiny):
    """The tiny bag damaged as a disk or a kill damages it (issue 53): cut at the start of its
    index, cut inside its chunk, a flipped byte in its index data, a chunk that claims 4 GiB, and
    the header of a bag never closed (index_pos 0, no index)."""
    records = bag_records(tiny)
    chunk = next(r for r in records if r[1] == 5)
    index_data = next(r for r in records if r[1] == 4)
    index = next(r for r in records if r[1] in (6, 7))
    write("rosbag", "cut-at-index.bag", tiny[:index[0]])
    write("rosbag", "cut-inside-chunk.bag", tiny[:chunk[2] + chunk[3] // 2])
    flipped = bytearray(tiny)
    flipped[index_data[2] + 8 + 3] ^= 0x40  # the high byte of the first message's offset
    write("rosbag", "flipped-index.bag", bytes(flipped))
    claims = bytearray(tiny)
    struct.pack_into("<I", claims, chunk[4][b"size"], 0xFFFFFFFF)
    write("rosbag", "claims-4GiB.bag", bytes(claims))
    unclosed = bytearray(tiny[:index[0]])
    struct.pack_into("<Q", unclosed, records[0][4][b"index_pos"], 0)
    write("rosbag", "unclosed.bag", bytes(unclosed))


def mcap_record(op, body):
    """An MCAP record: its opcode, its length (8 bytes), its body."""
    return bytes([op]) + struct.pack("<Q", len(body)) + body


def mcap_string(text):
    """An MCAP string: its length (4 bytes), its bytes."""
    return struct.pack("<I", len(text)) + text.encode()


def mcap_ros1_schemas_and_channels():
    """The schema (3) and channel (4) records of a cloud on /camera/depth/points (1) and tf on
    /tf (2), in ROS 1 serialization."""
    record, string = mcap_record, mcap_string
    schemas = (record(3, struct.pack("<H", 1) + string("sensor_msgs/PointCloud2") + string("ros1msg") +
                      struct.pack("<I", 0)) +
               record(3, struct.pack("<H", 2) + string("tf2_msgs/TFMessage") + string("ros1msg") +
                      struct.pack("<I", 0)))
    channels = (record(4, struct.pack("<HH", 1, 1) + string("/camera/depth/points") + string("ros1") +
                       struct.pack("<I", 0)) +
                record(4, struct.pack("<HH", 2, 2) + string("/tf") + string("ros1") +
                       struct.pack("<I", 0)))
    return schemas, channels


def mcap_seeds():
    """Tiny MCAP files by hand (mcap.dev/spec): the messages in ROS 1 serialization, one file
    without chunks and one with an uncompressed chunk."""
    record, string = mcap_record, mcap_string
    cloud, tf = cloud_and_tf_ros1()
    schemas, channels = mcap_ros1_schemas_and_channels()
    messages = (record(5, struct.pack("<HIQQ", 2, 0, 7_000_000_500, 7_000_000_500) + tf) +
                record(5, struct.pack("<HIQQ", 1, 1, 7_000_000_500, 7_000_000_500) + cloud))
    magic = b"\x89MCAP0\r\n"
    header = record(1, string("ros1") + string("make_seeds.py"))
    footer = record(2, struct.pack("<QQI", 0, 0, 0))
    write("mcap", "tiny.mcap", magic + header + schemas + channels + messages + footer + magic)
    inner = schemas + channels + messages
    chunk = record(6, struct.pack("<QQQI", 0, 0, len(inner), 0) + string("") +
                   struct.pack("<Q", len(inner)) + inner)
    write("mcap", "chunked.mcap", magic + header + chunk + footer + magic)
    # The same chunk compressed by the zstd and lz4 command-line tools (frames as libzstd and
    # liblz4 write them), and a zstd chunk that claims 4 GB uncompressed: the reader must refuse it
    # without allocating the claim (a finding of 2026-11-28).
    for compression, tool in (("zstd", ["zstd", "-q", "-c"]), ("lz4", ["lz4", "-q", "-c"])):
        try:
            packed = subprocess.run(tool, input=inner, capture_output=True, check=True).stdout
        except (OSError, subprocess.CalledProcessError):
            print(f"make_seeds: no {tool[0]} tool; its MCAP seeds are left as they are")
            continue
        for name, size in ((f"{compression}.mcap", len(inner)),
                           (f"{compression}-lying-size.mcap", 4_177_461_442)):
            chunk = record(6, struct.pack("<QQQI", 0, 0, size, 0) + string(compression) +
                           struct.pack("<Q", len(packed)) + packed)
            write("mcap", name, magic + header + chunk + footer + magic)


def mcap_whole_and_damaged_seeds():
    """A tiny MCAP file with everything the format offers to check (mcap.dev/spec): a chunk with
    its CRC, its message indexes, the data end's CRC, a summary (schemas, channels, statistics, a
    chunk index) with its CRC, the footer and the closing magic; then damaged as a disk or a kill
    damages it (issue 53)."""
    import zlib

    record, string = mcap_record, mcap_string
    cloud, tf = cloud_and_tf_ros1()
    magic = b"\x89MCAP0\r\n"
    schemas, channels = mcap_ros1_schemas_and_channels()
    inner = schemas + channels
    offsets = {}
    for channel, payload in ((2, tf), (1, cloud)):
        offsets[channel] = len(inner)
        inner += record(5, struct.pack("<HIQQ", channel, 0, 7_000_000_500, 7_000_000_500) + payload)
    header = record(1, string("ros1") + string("make_seeds.py"))
    data = magic + header
    chunk_at = len(data)
    data += record(6, struct.pack("<QQQI", 7_000_000_500, 7_000_000_500, len(inner),
                                  zlib.crc32(inner)) + string("") + struct.pack("<Q", len(inner)) +
                   inner)
    for channel in (1, 2):
        data += record(7, struct.pack("<HI", channel, 16) +
                       struct.pack("<QQ", 7_000_000_500, offsets[channel]))
    data_end_at = len(data)
    data += record(15, struct.pack("<I", zlib.crc32(data)))
    summary_start = len(data)
    counts = struct.pack("<HQHQ", 1, 1, 2, 1)
    summary = (schemas + channels +
               record(11, struct.pack("<QHIIIIQQ", 2, 2, 2, 0, 0, 1, 7_000_000_500, 7_000_000_500) +
                      struct.pack("<I", len(counts)) + counts) +
               record(8, struct.pack("<QQQQ", 7_000_000_500, 7_000_000_500, chunk_at,
                                     9 + 40 + len(inner)) + struct.pack("<I", 0) +
                      struct.pack("<Q", 0) + string("") + struct.pack("<QQ", len(inner), len(inner))))
    data += summary
    footer_head = bytes([2]) + struct.pack("<Q", 20) + struct.pack("<QQ", summary_start, 0)
    whole = data + footer_head + struct.pack("<I", zlib.crc32(summary + footer_head)) + magic
    write("mcap", "whole.mcap", whole)
    write("mcap", "cut-at-data-end.mcap", whole[:data_end_at])
    write("mcap", "cut-inside-chunk.mcap", whole[:chunk_at + 60])
    write("mcap", "no-closing-magic.mcap", whole[:-8])
    flipped = bytearray(whole)
    flipped[chunk_at + 9 + 40 + offsets[1] + 40] ^= 0x01  # inside the cloud message
    write("mcap", "flipped-chunk.mcap", bytes(flipped))
    claims = bytearray(whole)
    struct.pack_into("<Q", claims, chunk_at + 9 + 16, 1 << 60)
    write("mcap", "claims-2e60.mcap", bytes(claims))
    write("mcap", "magic-only.mcap", magic)


if __name__ == "__main__":
    rosbag_seeds()
    mcap_seeds()
    mcap_whole_and_damaged_seeds()
    depth_png_seeds()
    tum_seeds()
    pcd_seeds()
    ply_seeds()
    manifest_seeds()
    scene_seeds()
    octomap_seeds()
