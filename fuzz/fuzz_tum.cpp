// SPDX-License-Identifier: MIT
// Fuzz target: the TUM trajectory reader (io::read_tum on a stream) and the
// poses the CLI makes of its records (to_stamped_poses, PoseTrajectory), at
// time origin 0 and at an epoch origin. io::InputError is the documented
// outcome of bad input; a trajectory read cleanly must hold what read_tum
// promises (at least one pose, finite values, strictly increasing times,
// quaternion norms >= 1e-6) and must make a PoseTrajectory without error.
// O(input) per input.

#include "support/expect.hpp"

#include <streamclust/io/tum.hpp>
#include <streamclust/motion/trajectory.hpp>
#include <streamclust/motion/tum_poses.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace io = streamclust::io;
using streamclust::fuzz::require;

void read_at(const std::string& text, io::TimeOrigin origin) {
  std::istringstream in(text);
  std::vector<io::TumRecord> records;
  if (!streamclust::fuzz::only_throws<io::InputError>([&] { records = io::read_tum(in, "input.tum", origin); })) return;
  require(!records.empty(), "a clean read has at least one pose");
  for (std::size_t i = 0; i < records.size(); ++i) {
    const io::TumRecord& r = records[i];
    const double v[8] = {r.t, r.tx, r.ty, r.tz, r.qx, r.qy, r.qz, r.qw};
    for (const double x : v) require(std::isfinite(x), "every value finite");
    require(std::sqrt(r.qx * r.qx + r.qy * r.qy + r.qz * r.qz + r.qw * r.qw) >= io::tum_min_quaternion_norm,
            "quaternion norm >= 1e-6");
    if (i > 0) require(r.t > records[i - 1].t, "times strictly increase");
  }
  // What the CLI's --poses does with the records (cli/poses.hpp): read_tum's
  // checks are PoseTrajectory's, so this must not throw.
  streamclust::fuzz::never_throws([&] { streamclust::PoseTrajectory trajectory(streamclust::to_stamped_poses(records)); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  read_at(text, io::TimeOrigin{});
  read_at(text, io::TimeOrigin{1700000000});
  return 0;
}
