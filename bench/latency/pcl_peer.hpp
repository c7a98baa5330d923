// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The optional PCL peer of the latency benchmark: pcl::EuclideanClusterExtraction
/// (kd-tree) on one window. Compiled (pcl_peer.cpp) only when PCL is found;
/// this interface carries no PCL type, so the rest of the program never sees
/// PCL's headers.

#include <cstddef>
#include <vector>

namespace streamclust::bench {

/// True when the program was built with the PCL peer.
bool pcl_peer_available();

/// Clusters `xyz` (x0, y0, z0, x1, ...) [m] with EuclideanClusterExtraction
/// at `tolerance` [m] (minimum cluster size 1, so every point is labelled).
/// Returns the wall time [us] of extract(), which builds the kd-tree and
/// extracts the clusters; copying into the PCL cloud is not timed. Writes
/// the number of clusters to `clusters`. Returns a negative value when the
/// peer is unavailable.
double pcl_euclidean_us(const std::vector<float>& xyz, float tolerance, std::size_t& clusters);

}  // namespace streamclust::bench
