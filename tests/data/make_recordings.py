#!/usr/bin/python3
"""Makes the recordings of issue 38 from the shared Kinect frame (tests/data/real/), at test time.

usage: make_recordings.py OUT_DIR

Three depth frames: the Kinect frame's depth (16-bit, 5000 units a metre, 0 where it has none),
and the same points seen from two poses moved by known small motions (1-2 cm, 1.5-3 degrees),
rendered with a depth buffer. Written by this script alone (numpy, zlib and struct: no Vantage
code), in every layout Vantage reads:

  OUT_DIR/tum/            a TUM RGB-D folder: depth/*.png, depth.txt, groundtruth.txt
  OUT_DIR/pcd/*.pcd       the same frames as binary PCD clouds, one point per pixel with depth
                          (x = (u - cx) z / fx, y = (v - cy) z / fy, rounded to float32)
  OUT_DIR/pcd.yaml        the manifest of the PCD clouds, posed by the TUM folder's ground truth
  OUT_DIR/tum.yaml        the manifest that names the TUM folder
  OUT_DIR/kinect.bag      a ROS 1 bag written by Debian's python3-rosbag: the clouds as
                          sensor_msgs/PointCloud2 on /camera/depth/points (frame
                          camera_depth_optical_frame), /tf world -> base_link at each frame's stamp
                          (the ground truth), /tf_static base_link -> camera_depth_optical_frame
                          and the depth images as sensor_msgs/Image (16UC1, 5000 units a metre)
                          on /camera/depth/image_raw with their sensor_msgs/CameraInfo
  OUT_DIR/bag.yaml        the manifest that names the bag (bag_image.yaml: its image topic)
  OUT_DIR/raw/*.u16       the depth images as raw little-endian 16-bit rows, for make_mcap.js
  OUT_DIR/mcap.yaml       the manifest that names OUT_DIR/kinect.mcap, which tests/data/make_mcap.js
                          writes from these frames with npm's @mcap/core (mcap_image.yaml: its
                          image topic)
  OUT_DIR/bad/            depth images Vantage must refuse
"""

import os
import struct
import sys
import zlib

import numpy as np

FX, FY, CX, CY, W, H = 525.0, 525.0, 319.5, 239.5, 640, 480
SCALE = 5000.0  # units a metre, TUM RGB-D's
STAMPS = ["1305031102.175304", "1305031102.211214", "1305031102.243211"]
HERE = os.path.dirname(os.path.abspath(__file__))
KINECT = os.path.join(HERE, "real", "milk_cartoon_all_small_clorox.pcd")


def lzf_decompress(data, size):
    out = bytearray()
    i = 0
    while i < len(data):
        ctrl = data[i]
        i += 1
        if ctrl < 32:
            out += data[i:i + ctrl + 1]
            i += ctrl + 1
            continue
        length = ctrl >> 5
        ref = len(out) - ((ctrl & 0x1F) << 8) - 1
        if length == 7:
            length += data[i]
            i += 1
        ref -= data[i]
        i += 1
        for k in range(length + 2):
            out.append(out[ref + k])
    assert len(out) == size, (len(out), size)
    return bytes(out)


def kinect_depth():
    """The Kinect frame's z per pixel [m], NaN where it has no depth."""
    raw = open(KINECT, "rb").read()
    end = raw.index(b"DATA binary_compressed\n") + len(b"DATA binary_compressed\n")
    compressed, size = struct.unpack_from("<II", raw, end)
    soa = lzf_decompress(raw[end + 8:end + 8 + compressed], size)
    n = W * H
    z = np.frombuffer(soa, dtype="<f4", count=n, offset=2 * 4 * n)  # x's, y's, then z's
    return z.reshape(H, W).astype(np.float64)


def rotation(axis, deg):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    a = np.radians(deg)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k


def motion(t, axis, deg):
    m = np.eye(4)
    m[:3, :3] = rotation(axis, deg)
    m[:3, 3] = t
    return m


def back_project(depth):
    """Float32 points of the pixels with depth, row by row, as Vantage's depth_to_points."""
    v, u = np.nonzero(depth)
    z = depth[v, u].astype(np.float64) / SCALE
    x = (u.astype(np.float64) - CX) * z / FX
    y = (v.astype(np.float64) - CY) * z / FY
    return np.stack([x, y, z], axis=1).astype(np.float32)


def render(points, T_new_old):
    """A depth image of `points` (metres, old camera frame) seen from the moved camera."""
    p = points.astype(np.float64) @ T_new_old[:3, :3].T + T_new_old[:3, 3]
    p = p[p[:, 2] > 0.1]
    u = np.rint(FX * p[:, 0] / p[:, 2] + CX).astype(int)
    v = np.rint(FY * p[:, 1] / p[:, 2] + CY).astype(int)
    d = np.rint(p[:, 2] * SCALE).astype(np.int64)
    inside = (u >= 0) & (u < W) & (v >= 0) & (v < H) & (d > 0) & (d < 65536)
    u, v, d = u[inside], v[inside], d[inside]
    image = np.full((H, W), 65535, np.int64)
    np.minimum.at(image, (v, u), d)  # the nearest surface wins
    image[image == 65535] = 0
    return image.astype(np.uint16)


def png_chunk(kind, body):
    return (struct.pack(">I", len(body)) + kind + body +
            struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))


def write_png(path, image, bit_depth=16):
    height, width = image.shape
    sample = ">u2" if bit_depth == 16 else "u1"
    rows = b"".join(b"\x00" + image[r].astype(sample).tobytes() for r in range(height))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, 0, 0, 0, 0)))
        f.write(png_chunk(b"IDAT", zlib.compress(rows, 6)))
        f.write(png_chunk(b"IEND", b""))


def write_pcd(path, points):
    header = ("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
              f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {len(points)}\n"
              "DATA binary\n")
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(points.astype("<f4").tobytes())


def quaternion(r):
    """(x, y, z, w) of a rotation matrix."""
    w = np.sqrt(max(0.0, 1 + r[0, 0] + r[1, 1] + r[2, 2])) / 2
    x = np.copysign(np.sqrt(max(0.0, 1 + r[0, 0] - r[1, 1] - r[2, 2])) / 2, r[2, 1] - r[1, 2])
    y = np.copysign(np.sqrt(max(0.0, 1 - r[0, 0] + r[1, 1] - r[2, 2])) / 2, r[0, 2] - r[2, 0])
    z = np.copysign(np.sqrt(max(0.0, 1 - r[0, 0] - r[1, 1] + r[2, 2])) / 2, r[1, 0] - r[0, 1])
    return x, y, z, w


# The first camera: 0.46 m above a table at 0.75 m, 35 degrees down, as `vantage plan` places the
# Kinect frame (README: "A single Kinect frame with no pose"); optical axes.
R_SENSOR_CLOUD = np.array([[0, 0, 1], [-1, 0, 0], [0, -1, 0]], float)  # optical in x-forward
T_WORLD_CLOUD0 = np.eye(4)
T_WORLD_CLOUD0[:3, :3] = rotation([0, 1, 0], 34.727) @ R_SENSOR_CLOUD
T_WORLD_CLOUD0[:3, 3] = [-0.7476, -0.0078, 1.2142]
MOTIONS = [np.eye(4), motion([0.012, -0.004, 0.006], [0.2, 1.0, 0.1], 1.5),
           motion([0.020, -0.010, 0.004], [0.1, 1.0, -0.3], 3.0)]

SETTINGS = """sensor:
  frame: optical
  intrinsics: {fx: 525.0, fy: 525.0, cx: 319.5, cy: 239.5, width: 640, height: 480}
  min_range: 0.4
  max_range: 3.0
roi: {min: [-0.4, -0.4, 0.7], max: [0.4, 0.4, 1.1]}
resolution: 0.01
options: {table_segmentation: true}
"""


def write_bag(path, stamps, clouds, poses, images):
    """The frames as a ROS 1 bag, by Debian's python3-rosbag and its generated messages."""
    try:
        import genpy
        import rosbag
        from geometry_msgs.msg import TransformStamped
        from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField
        from tf2_msgs.msg import TFMessage
    except ImportError as e:
        sys.exit(f"make_recordings: {e}: install python3-rosbag, python3-sensor-msgs and "
                 "python3-tf2-msgs (scripts/install-deps.sh)")

    def transform(stamp, parent, child, pose):
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id = parent
        t.child_frame_id = child
        t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = (
            float(c) for c in pose[:3, 3])
        q = t.transform.rotation
        q.x, q.y, q.z, q.w = (float(c) for c in quaternion(pose[:3, :3]))
        return t

    info = CameraInfo()
    info.height, info.width = H, W
    info.distortion_model = "plumb_bob"
    info.D = [0.0] * 5
    info.K = [FX, 0, CX, 0, FY, CY, 0, 0, 1]
    info.R = [1.0, 0, 0, 0, 1, 0, 0, 0, 1]
    info.P = [FX, 0, CX, 0, 0, FY, CY, 0, 0, 0, 1, 0]
    with rosbag.Bag(path, "w") as bag:  # NOTE: uncompressed chunks, rosbag's default
        first = genpy.Time(*(int(x) for x in stamps[0].split(".")))
        static = TFMessage([transform(first, "base_link", "camera_depth_optical_frame", np.eye(4))])
        bag.write("/tf_static", static, first)
        for stamp_text, points, pose, depth in zip(stamps, clouds, poses, images):
            sec, frac = stamp_text.split(".")
            stamp = genpy.Time(int(sec), int(frac.ljust(9, "0")))
            bag.write("/tf", TFMessage([transform(stamp, "world", "base_link", pose)]), stamp)
            cloud = PointCloud2()
            cloud.header.stamp = stamp
            cloud.header.frame_id = "camera_depth_optical_frame"
            cloud.height, cloud.width = 1, len(points)
            cloud.fields = [PointField(n, 4 * i, PointField.FLOAT32, 1)
                            for i, n in enumerate("xyz")]
            cloud.is_bigendian = False
            cloud.point_step, cloud.row_step = 12, 12 * len(points)
            cloud.data = points.astype("<f4").tobytes()
            cloud.is_dense = True
            bag.write("/camera/depth/points", cloud, stamp)
            info.header.stamp = stamp
            info.header.frame_id = "camera_depth_optical_frame"
            bag.write("/camera/depth/camera_info", info, stamp)
            image = Image()
            image.header = info.header
            image.height, image.width = H, W
            image.encoding = "16UC1"
            image.is_bigendian = 0
            image.step = 2 * W
            image.data = depth.astype("<u2").tobytes()
            bag.write("/camera/depth/image_raw", image, stamp)


def frames():
    """The three depth images, and each camera's pose (optical frame in the world)."""
    z = kinect_depth()
    first = np.where(np.isfinite(z), np.rint(np.nan_to_num(z) * SCALE), 0).astype(np.uint16)
    points = back_project(first)
    images = [first] + [render(points, np.linalg.inv(m)) for m in MOTIONS[1:]]
    return images, [T_WORLD_CLOUD0 @ m for m in MOTIONS]


def main(out):
    for sub in ("tum/depth", "pcd", "bad"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    images, poses = frames()
    depth_txt = ["# depth maps", "# file: made by tests/data/make_recordings.py",
                 "# timestamp filename"]
    truth = ["# ground truth trajectory", "# timestamp tx ty tz qx qy qz qw"]
    for stamp, image, pose in zip(STAMPS, images, poses):
        write_png(os.path.join(out, "tum", "depth", stamp + ".png"), image)
        write_pcd(os.path.join(out, "pcd", stamp + ".pcd"), back_project(image))
        depth_txt.append(f"{stamp} depth/{stamp}.png")
        t = pose[:3, 3]
        q = quaternion(pose[:3, :3])
        truth.append(stamp + " " + " ".join(f"{c:.17g}" for c in (*t, *q)))
    open(os.path.join(out, "tum", "depth.txt"), "w").write("\n".join(depth_txt) + "\n")
    open(os.path.join(out, "tum", "groundtruth.txt"), "w").write("\n".join(truth) + "\n")
    open(os.path.join(out, "tum.yaml"), "w").write(
        "tum: {folder: tum}\n" + SETTINGS.replace("  max_range: 3.0\n",
                                                  "  max_range: 3.0\n  depth: {scale: 5000}\n"))
    clouds = "".join(f"  - file: pcd/{s}.pcd\n" for s in STAMPS)
    open(os.path.join(out, "pcd.yaml"), "w").write(
        "clouds:\n" + clouds +
        "trajectory: {file: tum/groundtruth.txt, match: timestamp}\n" + SETTINGS)
    write_bag(os.path.join(out, "kinect.bag"), STAMPS, [back_project(i) for i in images], poses,
              images)
    os.makedirs(os.path.join(out, "raw"), exist_ok=True)
    for stamp, image in zip(STAMPS, images):
        open(os.path.join(out, "raw", stamp + ".u16"), "wb").write(image.astype("<u2").tobytes())
    image_settings = SETTINGS.replace("  max_range: 3.0\n", "  max_range: 3.0\n  depth: {scale: 5000}\n")
    for name, recording in (("bag_image", "kinect.bag"), ("mcap_image", "kinect.mcap")):
        open(os.path.join(out, name + ".yaml"), "w").write(
            f"recording: {{file: {recording}, topic: /camera/depth/image_raw}}\n" + image_settings)
    open(os.path.join(out, "bag.yaml"), "w").write(
        "recording: {file: kinect.bag, topic: /camera/depth/points, fixed_frame: world}\n" +
        SETTINGS)
    open(os.path.join(out, "mcap.yaml"), "w").write(
        "recording: {file: kinect.mcap, topic: /camera/depth/points}\n" + SETTINGS)
    # Refused: an 8-bit image, and the first frame cut short.
    write_png(os.path.join(out, "bad", "eight_bit.png"), (images[0] // 256).astype(np.uint8), 8)
    good = open(os.path.join(out, "tum", "depth", STAMPS[0] + ".png"), "rb").read()
    open(os.path.join(out, "bad", "truncated.png"), "wb").write(good[:len(good) // 2])


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
