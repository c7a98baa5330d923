// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Streaming KITTI Velodyne .bin reader: little-endian float32 x, y, z,
/// reflectance per point (16 bytes), no header, no time (a point rate is
/// required: t = index / rate).

#include <streamclust/io/error.hpp>
#include <streamclust/io/input_stream.hpp>
#include <streamclust/io/point_reader.hpp>
#include <streamclust/io/record.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace streamclust::io {

/// Reader of KITTI .bin files. See the file comment.
class KittiReader final : public PointReader {
 public:
  static constexpr std::size_t record_bytes = 16;

  KittiReader(const std::string& path, const ReadOptions& options) : PointReader(path), src_(path) {
    info_.format = Format::kitti;
    info_.encoding = "";
    info_.fields = {"x", "y", "z", "reflectance"};
    info_.has_intensity = true;
    if (src_.size() == 0) throw InputError(path_, "byte 0", "empty file: expected float32 x y z reflectance records");
    if (src_.size() != std::numeric_limits<std::uint64_t>::max()) {
      if (src_.size() % record_bytes != 0) {
        const std::uint64_t whole = src_.size() / record_bytes;
        throw InputError(path_, detail::where_byte(whole * record_bytes),
                         "partial record: file size " + std::to_string(src_.size()) +
                             " is not a multiple of 16 bytes (float32 x y z reflectance); the record starting at byte " +
                             std::to_string(whole * record_bytes) + " has only " +
                             std::to_string(src_.size() % record_bytes) + " bytes");
      }
      points_ = src_.size() / record_bytes;
      info_.declared_points = points_;
    }
    setup_time(options, TimeUnit::s);
    block_.resize(4096 * record_bytes);
  }

  std::size_t read(std::vector<Record>& out, std::size_t max_records) override {
    std::size_t n = 0;
    while (n < max_records) {
      const std::size_t want = std::min<std::size_t>(max_records - n, 4096);
      const std::size_t got = src_.read(reinterpret_cast<char*>(block_.data()), want * record_bytes);
      const std::size_t whole = got / record_bytes;
      for (std::size_t k = 0; k < whole; ++k) {
        const unsigned char* p = block_.data() + k * record_bytes;
        Record r;
        r.x = detail::load_le<float>(p);
        r.y = detail::load_le<float>(p + 4);
        r.z = detail::load_le<float>(p + 8);
        r.intensity = detail::load_le<float>(p + 12);
        r.t = next_time();
        out.push_back(r);
      }
      n += whole;
      done_ += whole;
      if (got % record_bytes != 0) {
        throw InputError(path_, detail::where_byte(done_ * record_bytes),
                         "partial record: file ends " + std::to_string(got % record_bytes) +
                             " bytes into a 16-byte record (float32 x y z reflectance)");
      }
      if (got < want * record_bytes) break;
    }
    return n;
  }

 private:
  detail::ByteSource src_;
  std::uint64_t points_ = 0;
  std::uint64_t done_ = 0;
  std::vector<unsigned char> block_;
};

}  // namespace streamclust::io
