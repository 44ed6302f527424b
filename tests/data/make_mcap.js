// Writes OUT_DIR/kinect.mcap from the frames tests/data/make_recordings.py made in OUT_DIR (its
// pcd/*.pcd clouds and tum/groundtruth.txt), with independent writers: npm's @mcap/core (the MCAP
// container, chunked, uncompressed) and @foxglove/rosmsg2-serialization (ROS 2 CDR messages),
// as scripts/fetch-mcap-writer.sh pins and fetches them. The same layout as the bag:
// sensor_msgs/msg/PointCloud2 on /camera/depth/points (camera_depth_optical_frame), /tf world ->
// base_link at each frame's stamp, /tf_static base_link -> camera_depth_optical_frame, and the
// depth images (raw/*.u16) as sensor_msgs/msg/Image (16UC1) on /camera/depth/image_raw with their
// sensor_msgs/msg/CameraInfo.
//
// usage: node make_mcap.js OUT_DIR NODE_MODULES_DIR
"use strict";
const fs = require("fs");
const path = require("path");

const [out, modulesArg] = process.argv.slice(2);
const modules = modulesArg && path.resolve(modulesArg);
if (!out || !modules) {
  console.error("usage: node make_mcap.js OUT_DIR NODE_MODULES_DIR");
  process.exit(2);
}
let McapWriter, MessageWriter;
try {
  ({ McapWriter } = require(path.join(modules, "@mcap/core")));
  ({ MessageWriter } = require(path.join(modules, "@foxglove/rosmsg2-serialization")));
} catch (e) {
  console.error(`make_mcap: ${e.message.split("\n")[0]}: run scripts/fetch-mcap-writer.sh`);
  process.exit(1);
}

const f = (type, name, extra = {}) => ({ type, name, isComplex: false, ...extra });
const c = (type, name, extra = {}) => ({ type, name, isComplex: true, ...extra });
const kTypes = {
  "builtin_interfaces/msg/Time": [f("int32", "sec"), f("uint32", "nanosec")],
  "std_msgs/msg/Header": [c("builtin_interfaces/msg/Time", "stamp"), f("string", "frame_id")],
  "sensor_msgs/msg/PointField": [
    f("string", "name"), f("uint32", "offset"), f("uint8", "datatype"), f("uint32", "count")],
  "sensor_msgs/msg/PointCloud2": [
    c("std_msgs/msg/Header", "header"), f("uint32", "height"), f("uint32", "width"),
    c("sensor_msgs/msg/PointField", "fields", { isArray: true }), f("bool", "is_bigendian"),
    f("uint32", "point_step"), f("uint32", "row_step"), f("uint8", "data", { isArray: true }),
    f("bool", "is_dense")],
  "geometry_msgs/msg/Vector3": [f("float64", "x"), f("float64", "y"), f("float64", "z")],
  "geometry_msgs/msg/Quaternion": [
    f("float64", "x"), f("float64", "y"), f("float64", "z"), f("float64", "w")],
  "geometry_msgs/msg/Transform": [
    c("geometry_msgs/msg/Vector3", "translation"), c("geometry_msgs/msg/Quaternion", "rotation")],
  "geometry_msgs/msg/TransformStamped": [
    c("std_msgs/msg/Header", "header"), f("string", "child_frame_id"),
    c("geometry_msgs/msg/Transform", "transform")],
  "sensor_msgs/msg/Image": [
    c("std_msgs/msg/Header", "header"), f("uint32", "height"), f("uint32", "width"),
    f("string", "encoding"), f("uint8", "is_bigendian"), f("uint32", "step"),
    f("uint8", "data", { isArray: true })],
  "sensor_msgs/msg/RegionOfInterest": [
    f("uint32", "x_offset"), f("uint32", "y_offset"), f("uint32", "height"), f("uint32", "width"),
    f("bool", "do_rectify")],
  "sensor_msgs/msg/CameraInfo": [
    c("std_msgs/msg/Header", "header"), f("uint32", "height"), f("uint32", "width"),
    f("string", "distortion_model"), f("float64", "d", { isArray: true }),
    f("float64", "k", { isArray: true, arrayLength: 9 }), f("float64", "r", { isArray: true, arrayLength: 9 }),
    f("float64", "p", { isArray: true, arrayLength: 12 }), f("uint32", "binning_x"), f("uint32", "binning_y"),
    c("sensor_msgs/msg/RegionOfInterest", "roi")],
  "tf2_msgs/msg/TFMessage": [
    c("geometry_msgs/msg/TransformStamped", "transforms", { isArray: true })],
};
// The root first, then every type it uses, as MessageWriter takes them.
const definitions = (root) => [
  { name: root, definitions: kTypes[root] },
  ...Object.entries(kTypes).filter(([n]) => n !== root).map(([name, defs]) => ({ name, definitions: defs })),
];
// The schema text (ros2msg): each type's fields, the used types after a separator line.
const schemaText = (root) => definitions(root).map((d, i) =>
  (i > 0 ? `================================================================================\nMSG: ${d.name.replace("/msg/", "/")}\n` : "") +
  d.definitions.map((x) => `${x.type.replace("/msg/", "/")}${x.isArray ? "[]" : ""} ${x.name}`).join("\n")).join("\n");

function readPcd(file) {
  const raw = fs.readFileSync(file);
  const end = raw.indexOf("DATA binary\n") + "DATA binary\n".length;
  return raw.subarray(end);  // x, y, z float32 per point, little-endian
}

function stampOf(text) {
  const [sec, frac] = text.split(".");
  return { sec: Number(sec), nanosec: Number(frac.padEnd(9, "0")) };
}

const transform = (stamp, parent, child, t, q) => ({
  header: { stamp, frame_id: parent }, child_frame_id: child,
  transform: { translation: { x: t[0], y: t[1], z: t[2] }, rotation: { x: q[0], y: q[1], z: q[2], w: q[3] } },
});

async function main() {
  const truth = fs.readFileSync(path.join(out, "tum", "groundtruth.txt"), "utf8").split("\n")
    .filter((l) => l && !l.startsWith("#")).map((l) => l.split(" "));
  const chunks = [];
  let position = 0n;
  const writable = {
    position: () => position,
    write: async (buffer) => { chunks.push(Buffer.from(buffer)); position += BigInt(buffer.byteLength); },
  };
  const writer = new McapWriter({ writable });
  await writer.start({ profile: "ros2", library: "@mcap/core 2.2.2 (tests/data/make_mcap.js)" });
  const channel = async (topic, type) => {
    const schemaId = await writer.registerSchema({
      name: type, encoding: "ros2msg", data: new TextEncoder().encode(schemaText(type)) });
    return writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map() });
  };
  const tf = await channel("/tf", "tf2_msgs/msg/TFMessage");
  const tfStatic = await channel("/tf_static", "tf2_msgs/msg/TFMessage");
  const points = await channel("/camera/depth/points", "sensor_msgs/msg/PointCloud2");
  const images = await channel("/camera/depth/image_raw", "sensor_msgs/msg/Image");
  const infos = await channel("/camera/depth/camera_info", "sensor_msgs/msg/CameraInfo");
  const imageWriter = new MessageWriter(definitions("sensor_msgs/msg/Image"));
  const infoWriter = new MessageWriter(definitions("sensor_msgs/msg/CameraInfo"));
  const tfWriter = new MessageWriter(definitions("tf2_msgs/msg/TFMessage"));
  const cloudWriter = new MessageWriter(definitions("sensor_msgs/msg/PointCloud2"));
  const time = (s) => BigInt(s.sec) * 1000000000n + BigInt(s.nanosec);
  let sequence = 0;
  const add = (channelId, stamp, data) => writer.addMessage({
    channelId, sequence: sequence++, logTime: time(stamp), publishTime: time(stamp), data });

  const first = stampOf(truth[0][0]);
  await add(tfStatic, first, tfWriter.writeMessage({ transforms: [
    transform(first, "base_link", "camera_depth_optical_frame", [0, 0, 0], [0, 0, 0, 1])] }));
  for (const row of truth) {
    const stamp = stampOf(row[0]);
    const v = row.slice(1).map(Number);
    await add(tf, stamp, tfWriter.writeMessage({ transforms: [
      transform(stamp, "world", "base_link", v.slice(0, 3), v.slice(3, 7))] }));
    const data = readPcd(path.join(out, "pcd", `${row[0]}.pcd`));
    const n = data.length / 12;
    await add(points, stamp, cloudWriter.writeMessage({
      header: { stamp, frame_id: "camera_depth_optical_frame" }, height: 1, width: n,
      fields: ["x", "y", "z"].map((name, i) => ({ name, offset: 4 * i, datatype: 7, count: 1 })),
      is_bigendian: false, point_step: 12, row_step: 12 * n, data: new Uint8Array(data), is_dense: true,
    }));
  }
  for (const row of truth) {
    const stamp = stampOf(row[0]);
    const header = { stamp, frame_id: "camera_depth_optical_frame" };
    const [fx, fy, cx, cy, w, h] = [525.0, 525.0, 319.5, 239.5, 640, 480];
    await add(infos, stamp, infoWriter.writeMessage({
      header, height: h, width: w, distortion_model: "plumb_bob", d: [0, 0, 0, 0, 0],
      k: [fx, 0, cx, 0, fy, cy, 0, 0, 1], r: [1, 0, 0, 0, 1, 0, 0, 0, 1],
      p: [fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0], binning_x: 0, binning_y: 0,
      roi: { x_offset: 0, y_offset: 0, height: 0, width: 0, do_rectify: false } }));
    const raw = fs.readFileSync(path.join(out, "raw", `${row[0]}.u16`));
    await add(images, stamp, imageWriter.writeMessage({
      header, height: h, width: w, encoding: "16UC1", is_bigendian: 0, step: 2 * w,
      data: new Uint8Array(raw) }));
  }
  await writer.end();
  fs.writeFileSync(path.join(out, "kinect.mcap"), Buffer.concat(chunks));
}

main().catch((e) => { console.error(`make_mcap: ${e.message}`); process.exit(1); });
