#include "vantage/io/cloud_io.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "temp_dir.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

class CloudIo : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& bytes) const {
    test::write_file(dir_ / name, bytes);
    return dir_ / name;
  }

  test::TempDir dir_;
};

/// Points whose coordinates are exact in float, so a round trip must return them unchanged.
PointCloud float_exact_cloud(std::size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) cloud.emplace_back(u(rng), u(rng), u(rng));
  return cloud;
}

/// The message of the exception `read` throws, checked to be of type E and one line long.
template <typename E>
std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no exception";
  return {};
}

std::string read_error(const fs::path& path) {
  return error_of<std::runtime_error>([&] { read_point_cloud(path); });
}

constexpr const char* kPcdHeader =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
    "TYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\n";

TEST_F(CloudIo, PcdAndPlyRoundTripExactly) {
  const PointCloud cloud = float_exact_cloud(1000);
  for (const char* name : {"a.pcd", "a.ply", "UPPER.PCD"}) {
    write_point_cloud(dir_ / name, cloud);
    EXPECT_EQ(read_point_cloud(dir_ / name), cloud) << name;
  }
}

TEST_F(CloudIo, APcdRecordsItsViewpoint) {
  const PointCloud cloud = float_exact_cloud(10);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(-1.25, 0.5, 1.1);
  write_point_cloud(dir_ / "posed.pcd", cloud, pose);
  EXPECT_EQ(read_point_cloud(dir_ / "posed.pcd"), cloud);
  const std::optional<Eigen::Isometry3d> read = read_cloud_viewpoint(dir_ / "posed.pcd");
  ASSERT_TRUE(read.has_value());
  EXPECT_TRUE(read->isApprox(pose, 1e-14)) << read->matrix();
  // The identity is what writers put there when nobody set a pose: no pose. PLY has no field.
  write_point_cloud(dir_ / "plain.pcd", cloud);
  EXPECT_FALSE(read_cloud_viewpoint(dir_ / "plain.pcd").has_value());
  write_point_cloud(dir_ / "posed.ply", cloud, pose);
  EXPECT_FALSE(read_cloud_viewpoint(dir_ / "posed.ply").has_value());
  // A malformed VIEWPOINT names the file and the line.
  const fs::path bad =
      write("bad.pcd", std::string(kPcdHeader)
                               .replace(std::string(kPcdHeader).find("VIEWPOINT 0 0 0 1 0 0 0"), 23,
                                        "VIEWPOINT 0 0 0 1 0 0") +
                           "DATA ascii\n1 2 3\n4 5 6\n7 8 9\n");
  const std::string message =
      error_of<std::runtime_error>([&] { (void)read_cloud_viewpoint(bad); });
  EXPECT_NE(message.find("bad.pcd: line 9: VIEWPOINT takes 7 numbers"), std::string::npos)
      << message;
}

// issue 53: a PLY file whose data is in the other byte order than its header says was blamed on
// a NaN, with the advice to skip non-finite points.
TEST_F(CloudIo, APlyInTheOtherByteOrderIsSaidAsSuch) {
  // Little-endian floats whose bytes, reversed, are NaN: 0x3f80ffff (1.0000305).
  std::string data;
  for (int i = 0; i < 3; ++i) data += std::string("\xff\xff\x80\x3f", 4);
  const fs::path path = write("swapped.ply",
                              "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float "
                              "x\nproperty float y\nproperty float z\nend_header\n" +
                                  data);
  const std::string message = error_of<std::runtime_error>([&] { (void)read_point_cloud(path); });
  EXPECT_NE(message.find("swapped.ply: point 0 has a non-finite coordinate"), std::string::npos)
      << message;
  EXPECT_NE(message.find("; read as binary_little_endian every point is finite: its header names "
                         "the wrong byte order"),
            std::string::npos)
      << message;
}

// issue 53: a VIEWPOINT 1e300 m away was taken as the cloud's pose, and the cloud mapped with a
// warning that none of its points lay in the roi.
TEST_F(CloudIo, AViewpointPastTheWorldIsRefused) {
  for (const std::string far : {"1e300 0 0", "0 -2e5 0"}) {
    const fs::path path =
        write("far.pcd", std::string(kPcdHeader)
                                 .replace(std::string(kPcdHeader).find("VIEWPOINT 0 0 0 1 0 0 0"),
                                          23, "VIEWPOINT " + far + " 1 0 0 0") +
                             "DATA ascii\n1 2 3\n4 5 6\n7 8 9\n");
    const std::string message =
        error_of<std::runtime_error>([&] { (void)read_cloud_viewpoint(path); });
    EXPECT_NE(message.find("far.pcd: line 9: the VIEWPOINT's position ("), std::string::npos)
        << message;
    EXPECT_NE(message.find("lies farther from the origin than the 100000 m"), std::string::npos)
        << message;
  }
}

TEST_F(CloudIo, DoublesRoundTripToFloatPrecision) {
  const PointCloud cloud = {{0.1, 0.2, 0.3}, {1.0 / 3.0, -2.0 / 7.0, 1e-9}};
  write_point_cloud(dir_ / "d.pcd", cloud);
  const PointCloud back = read_point_cloud(dir_ / "d.pcd");
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LT((back[i] - cloud[i]).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_NE(back[i], cloud[i]);  // float rounding is real, and documented
  }
}

TEST_F(CloudIo, ReadsAsciiPcdWithOtherFieldsAndComments) {
  const fs::path path = write("rgb.pcd",
                              "# comment\nVERSION .7\nFIELDS rgb normal x y z\nSIZE 4 4 8 8 4\n"
                              "TYPE F F F F U\nCOUNT 1 3 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
                              "DATA ascii\n4.2e6 0 0 1 1.5 -2.25 7\r\n\n1 0 1 0 +3 4e-1 9\n");
  const PointCloud cloud = read_point_cloud(path);
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud[0], Eigen::Vector3d(1.5, -2.25, 7.0));
  EXPECT_EQ(cloud[1], Eigen::Vector3d(3.0, 0.4, 9.0));
}

TEST_F(CloudIo, ReadsBinaryPcdWithPaddingFields) {
  // x as double, an int16 field between, z before y: offsets follow the FIELDS order.
  std::string body;
  const auto put = [&body](const auto value) {
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    body.append(bytes, sizeof(value));
  };
  put(1.25);
  put(std::int16_t{-3});
  put(0.5f);
  put(std::uint8_t{200});
  put(-4.0f);
  const fs::path path =
      write("b.pcd", std::string("VERSION 0.7\nFIELDS x pad z label y\nSIZE 8 2 4 1 4\n"
                                 "TYPE F I F U F\nWIDTH 1\nPOINTS 1\nDATA binary\n") +
                         body);
  EXPECT_EQ(read_point_cloud(path), PointCloud{Eigen::Vector3d(1.25, -4.0, 0.5)});
}

TEST_F(CloudIo, ReadsPlyWithOtherElementsAndLists) {
  const fs::path ascii =
      write("mesh.ply",
            "ply\nformat ascii 1.0\ncomment made by hand\nelement camera 1\nproperty float f\n"
            "element vertex 2\nproperty uchar red\nproperty double x\nproperty list uchar int "
            "idx\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int "
            "vertex_indices\nend_header\n0.5\n255 1.5 2 7 8 2.5 3.5\n0 -1 0 -2 -3\n3 0 1 1\n");
  EXPECT_EQ(read_point_cloud(ascii),
            (PointCloud{Eigen::Vector3d(1.5, 2.5, 3.5), Eigen::Vector3d(-1, -2, -3)}));

  // Big endian, with a list element before the vertices.
  std::string body;
  const auto put_be = [&body](const auto value) {
    char bytes[sizeof(value)];
    std::memcpy(bytes, &value, sizeof(value));
    for (std::size_t i = sizeof(value); i-- > 0;) body.push_back(bytes[i]);
  };
  put_be(std::uint8_t{2});
  put_be(std::int32_t{5});
  put_be(std::int32_t{6});
  put_be(1.0f);
  put_be(std::int16_t{-2});
  put_be(3.0);
  const fs::path binary =
      write("be.ply",
            "ply\nformat binary_big_endian 1.0\nelement junk 1\nproperty list uchar int l\n"
            "element vertex 1\nproperty float x\nproperty short y\nproperty double z\n"
            "end_header\n" +
                body);
  EXPECT_EQ(read_point_cloud(binary), PointCloud{Eigen::Vector3d(1.0, -2.0, 3.0)});
}

TEST_F(CloudIo, MalformedFilesNameTheFileAndWhere) {
  struct Case {
    const char* name;
    std::string bytes;
    const char* expect;  // a piece of the message
  };
  const std::string binary_body(20, 'x');  // 3 points need 36 bytes
  const Case cases[] = {
      {"junk.pcd", "hello world\n", "unknown PCD header key 'hello'"},
      {"noheader.pcd", "", "no DATA line"},
      {"short.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n4 5 6\n", "ends after 2 of"},
      {"long.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n4 5 6\n7 8 9\n1 1 1\n",
       "line 15: more points"},
      {"garbage.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n4 5 6\n7 abc 9\n",
       "line 14: 'abc' is not a number"},
      {"columns.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n4 5\n7 8 9\n",
       "line 13: expected 3 values, found 2"},
      {"trunc.pcd", std::string(kPcdHeader) + "DATA binary\n" + binary_body,
       "binary data holds 20 bytes, expected 3 points"},
      {"huge.pcd",
       "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 4000000000000\nDATA binary\n" + binary_body,
       "expected 4000000000000 points x 12 bytes"},
      {"noz.pcd", "FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA ascii\n1 2\n", "no field 'z'"},
      {"mismatch.pcd", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n",
       "3 FIELDS but 2 SIZE"},
      {"half.pcd", "FIELDS x y z\nSIZE 2 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n",
       "not a supported scalar"},
      {"compressed.pcd", std::string(kPcdHeader) + "DATA binary_compressed\n" + binary_body,
       "binary_compressed"},
      {"notply.ply", "PLY\n", "not a PLY file"},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "no end_header"},
      {"short.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
       "float z\nend_header\n1 2 3\n4 5 6\n",
       "ends after 2 of the 3 vertices"},
      {"garbage.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty "
       "float z\nend_header\n1 2 3\n4 x 6\n",
       "line 9: 'x' is not a number"},
      {"trunc.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
       "y\nproperty float z\nend_header\n123456789012",
       "declares 3 vertices"},
      {"tail.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float "
       "y\nproperty float z\nend_header\n1234567890123",
       "1 bytes after its last vertex"},
      {"noxyz.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n"
       "1 2\n",
       "no scalar property 'z'"},
  };
  for (const Case& c : cases) {
    const fs::path path = write(c.name, c.bytes);
    const std::string message = read_error(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
  }
}

TEST_F(CloudIo, NonFiniteCoordinatesNameThePoint) {
  const fs::path ascii =
      write("nan.pcd", std::string(kPcdHeader) + "DATA ascii\n1 2 3\n4 nan 6\n7 8 9\n");
  EXPECT_NE(read_error(ascii).find("nan.pcd: point 1 has a non-finite coordinate"),
            std::string::npos);

  std::string body;
  for (const float v :
       {1.f, 2.f, 3.f, 4.f, 5.f, 6.f, 7.f, 8.f, std::numeric_limits<float>::infinity()}) {
    body.append(reinterpret_cast<const char*>(&v), sizeof(v));
  }
  const fs::path binary = write("inf.pcd", std::string(kPcdHeader) + "DATA binary\n" + body);
  EXPECT_NE(read_error(binary).find("inf.pcd: point 2 has a non-finite coordinate"),
            std::string::npos);

  const fs::path ply = write("nan.ply",
                             "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty "
                             "float y\nproperty float z\nend_header\n1 2 3\n-inf 0 0\n");
  EXPECT_NE(read_error(ply).find("nan.ply: point 1 has"), std::string::npos);
}

TEST_F(CloudIo, NonFinitePointsCanBeSkippedOnRequest) {
  const fs::path path =
      write("organized.pcd", std::string(kPcdHeader) + "DATA ascii\nnan nan nan\n1 2 3\n4 5 inf\n");
  EXPECT_EQ(read_point_cloud(path, {.skip_non_finite = true}),
            PointCloud{Eigen::Vector3d(1, 2, 3)});
  const fs::path none =
      write("none.ply",
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
            "y\nproperty float z\nend_header\nnan 0 0\n");
  const std::string message =
      error_of<std::runtime_error>([&] { read_point_cloud(none, {.skip_non_finite = true}); });
  EXPECT_NE(message.find("none.ply: no point has finite coordinates"), std::string::npos);
}

TEST_F(CloudIo, EmptyCloudsAreErrors) {
  const fs::path pcd =
      write("empty.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 0\nPOINTS 0\nDATA ascii\n");
  EXPECT_NE(read_error(pcd).find("empty.pcd: the cloud is empty"), std::string::npos);
  const fs::path ply = write("empty.ply",
                             "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty "
                             "float y\nproperty float z\nend_header\n");
  EXPECT_NE(read_error(ply).find("empty.ply: the cloud is empty"), std::string::npos);

  const fs::path out = dir_ / "out.pcd";
  const std::string message =
      error_of<std::invalid_argument>([&] { write_point_cloud(out, PointCloud{}); });
  EXPECT_NE(message.find("out.pcd: refusing to write an empty point cloud"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CloudIo, MissingFilesAndOtherFormats) {
  EXPECT_NE(read_error(dir_ / "missing.pcd").find("missing.pcd: no such file"), std::string::npos);
  fs::create_directories(dir_ / "folder.pcd");
  EXPECT_NE(read_error(dir_ / "folder.pcd").find("folder.pcd: is a directory, not a file"),
            std::string::npos);
  // Issue 15: a FIFO, a symlink loop and a device are said as what they are, not "no such file".
  ASSERT_EQ(mkfifo((dir_ / "fifo.pcd").c_str(), 0600), 0);
  EXPECT_NE(read_error(dir_ / "fifo.pcd").find("fifo.pcd: is a FIFO, not a regular file"),
            std::string::npos);
  fs::create_symlink("loop.pcd", dir_ / "loop.pcd");
  EXPECT_NE(read_error(dir_ / "loop.pcd").find("loop.pcd: is a symlink loop"), std::string::npos);
  fs::create_symlink("/dev/zero", dir_ / "zero.pcd");
  EXPECT_NE(read_error(dir_ / "zero.pcd").find("zero.pcd: is a character device"),
            std::string::npos);
  const std::string message =
      error_of<std::invalid_argument>([&] { read_point_cloud(dir_ / "cloud.xyz"); });
  EXPECT_NE(message.find("cloud.xyz: unsupported point-cloud format '.xyz'"), std::string::npos);
  EXPECT_THROW(write_point_cloud(dir_ / "cloud", {{0, 0, 0}}), std::invalid_argument);
}

// issue 39: the kind sniffed from the content where an extension can lie.
TEST_F(CloudIo, AnExtensionThatLiesIsSaid) {
  const PointCloud cloud = float_exact_cloud(3);
  write_point_cloud(dir_ / "real.ply", cloud);
  write_point_cloud(dir_ / "real.pcd", cloud);
  fs::copy_file(dir_ / "real.ply", dir_ / "ply.pcd");
  fs::copy_file(dir_ / "real.pcd", dir_ / "pcd.ply");
  EXPECT_NE(read_error(dir_ / "ply.pcd")
                .find("ply.pcd: holds a PLY file, not what its .pcd "
                      "extension says"),
            std::string::npos)
      << read_error(dir_ / "ply.pcd");
  EXPECT_NE(read_error(dir_ / "pcd.ply")
                .find("pcd.ply: holds a PCD point cloud, not what its "
                      ".ply extension says"),
            std::string::npos)
      << read_error(dir_ / "pcd.ply");
  EXPECT_EQ(read_point_cloud(dir_ / "real.pcd").size(), 3u);
}

TEST_F(CloudIo, BadPointsAreRefusedAndTheOldFileKept) {
  const fs::path path = dir_ / "keep.ply";
  const PointCloud good = float_exact_cloud(10);
  write_point_cloud(path, good);
  for (const double bad : {std::nan(""), 1e39}) {  // 1e39 overflows float
    PointCloud cloud = good;
    cloud[4].y() = bad;
    const std::string message =
        error_of<std::invalid_argument>([&] { write_point_cloud(path, cloud); });
    EXPECT_NE(message.find("keep.ply: point 4 is not finite as float"), std::string::npos)
        << message;
  }
  EXPECT_EQ(read_point_cloud(path), good);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_.path()), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace vantage
