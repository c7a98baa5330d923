// SPDX-License-Identifier: MIT
// PCL's Euclidean cluster extraction as a peer; see pcl_peer.hpp. Built only
// when CMake finds PCL (STREAMCLUST_BENCH_HAVE_PCL); otherwise the stubs
// report the peer as unavailable.

#include "pcl_peer.hpp"

#ifdef STREAMCLUST_BENCH_HAVE_PCL
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <chrono>
#include <limits>
#endif

namespace streamclust::bench {

#ifdef STREAMCLUST_BENCH_HAVE_PCL

bool pcl_peer_available() { return true; }

double pcl_euclidean_us(const std::vector<float>& xyz, float tolerance, std::size_t& clusters) {
  auto cloud = pcl::PointCloud<pcl::PointXYZ>::Ptr(new pcl::PointCloud<pcl::PointXYZ>);
  const std::size_t n = xyz.size() / 3;
  cloud->points.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cloud->points[i].x = xyz[3 * i];
    cloud->points[i].y = xyz[3 * i + 1];
    cloud->points[i].z = xyz[3 * i + 2];
  }
  cloud->width = static_cast<std::uint32_t>(n);
  cloud->height = 1;
  cloud->is_dense = true;

  std::vector<pcl::PointIndices> found;
  const auto t0 = std::chrono::steady_clock::now();
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(static_cast<double>(tolerance));
  ec.setMinClusterSize(1);
  ec.setMaxClusterSize(std::numeric_limits<int>::max());
  ec.setSearchMethod(tree);
  ec.setInputCloud(cloud);
  ec.extract(found);
  const auto t1 = std::chrono::steady_clock::now();
  clusters = found.size();
  return std::chrono::duration<double, std::micro>(t1 - t0).count();
}

#else

bool pcl_peer_available() { return false; }

double pcl_euclidean_us(const std::vector<float>&, float, std::size_t& clusters) {
  clusters = 0;
  return -1.0;
}

#endif

}  // namespace streamclust::bench
