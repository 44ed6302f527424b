// Interoperability with PCL: files PCL writes read back here, and files written here load in PCL.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>
#include <unistd.h>

#include <filesystem>
#include <random>
#include <string>

#include "vantage/io/cloud_io.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

class CloudIoPcl : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vantage_cloud_io_pcl_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    for (int i = 0; i < 500; ++i) {
      const pcl::PointXYZ p(u(rng), u(rng), u(rng));
      pcl_cloud_.push_back(p);
      cloud_.emplace_back(p.x, p.y, p.z);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  pcl::PointCloud<pcl::PointXYZ> pcl_cloud_;
  PointCloud cloud_;
};

void expect_near(const PointCloud& a, const PointCloud& b, double tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_LE((a[i] - b[i]).cwiseAbs().maxCoeff(), tolerance) << "point " << i;
  }
}

TEST_F(CloudIoPcl, ReadsWhatPclWrites) {
  const std::string base = (dir_ / "pcl").string();
  ASSERT_EQ(pcl::io::savePCDFileBinary(base + "_binary.pcd", pcl_cloud_), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(base + "_compressed.pcd", pcl_cloud_), 0);
  ASSERT_EQ(pcl::io::savePCDFileASCII(base + "_ascii.pcd", pcl_cloud_), 0);
  ASSERT_EQ(pcl::io::savePLYFileBinary(base + "_binary.ply", pcl_cloud_), 0);
  ASSERT_EQ(pcl::io::savePLYFileASCII(base + "_ascii.ply", pcl_cloud_), 0);
  EXPECT_EQ(read_point_cloud(base + "_binary.pcd"), cloud_);
  EXPECT_EQ(read_point_cloud(base + "_compressed.pcd"), cloud_);
  EXPECT_EQ(read_point_cloud(base + "_binary.ply"), cloud_);
  // PCL writes ASCII with 8 significant digits.
  expect_near(read_point_cloud(base + "_ascii.pcd"), cloud_, 1e-6);
  expect_near(read_point_cloud(base + "_ascii.ply"), cloud_, 1e-6);
}

TEST_F(CloudIoPcl, PclReadsWhatWeWrite) {
  write_point_cloud(dir_ / "ours.pcd", cloud_);
  write_point_cloud(dir_ / "ours.ply", cloud_);
  for (const char* name : {"ours.pcd", "ours.ply"}) {
    pcl::PointCloud<pcl::PointXYZ> loaded;
    const std::string path = (dir_ / name).string();
    const bool pcd = fs::path(name).extension() == ".pcd";
    ASSERT_EQ(pcd ? pcl::io::loadPCDFile(path, loaded) : pcl::io::loadPLYFile(path, loaded), 0)
        << name;
    ASSERT_EQ(loaded.size(), pcl_cloud_.size()) << name;
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      EXPECT_EQ(loaded[i].getVector3fMap(), pcl_cloud_[i].getVector3fMap()) << name << " " << i;
    }
  }
}

}  // namespace
}  // namespace vantage
