// SPDX-License-Identifier: MIT
// Fuzz target: the message layer under every recording reader -- one
// serialized message decoded as a Livox CustomMsg or a sensor_msgs/PointCloud2,
// in ROS 1 or CDR encoding, into timed points (io/ros/point_messages.hpp).
// The first byte picks the case (bits 0-1: type and encoding; bit 2: a point
// rate for clouds without a time field); the rest is the message. Reaches
// what container CRCs and codecs shield from the container targets.
//
// A bug, besides a crash, undefined behaviour, a leak or unbounded memory or
// time: an exception other than io::InputError.

#include "support/expect.hpp"

#include <streamclust/io/error.hpp>
#include <streamclust/io/ros/known_definitions.hpp>
#include <streamclust/io/ros/point_messages.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace {

namespace io = streamclust::io;
namespace ros = streamclust::io::ros;

/// ROS 1 definitions (the bag's connection carries them; these follow the .msg files).
const std::string ros1_header = "================================================================================\n"
                                "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n";
const std::string ros1_custom = "Header header\nuint64 timebase\nuint32 point_num\nuint8 lidar_id\nuint8[3] rsvd\n"
                                "CustomPoint[] points\n"
                                "================================================================================\n"
                                "MSG: livox_ros_driver/CustomPoint\nuint32 offset_time\nfloat32 x\nfloat32 y\n"
                                "float32 z\nuint8 reflectivity\nuint8 tag\nuint8 line\n" + ros1_header;
const std::string ros1_cloud = "Header header\nuint32 height\nuint32 width\nPointField[] fields\nbool is_bigendian\n"
                               "uint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"
                               "================================================================================\n"
                               "MSG: sensor_msgs/PointField\nstring name\nuint32 offset\nuint8 datatype\nuint32 count\n" +
                               ros1_header;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const unsigned pick = data[0] & 3u;
  const bool custom = (pick & 1u) == 0;
  const ros::Encoding encoding = (pick & 2u) != 0 ? ros::Encoding::cdr : ros::Encoding::ros1;
  const char* type = custom ? (encoding == ros::Encoding::cdr ? "livox_ros_driver2/msg/CustomMsg" : "livox_ros_driver/CustomMsg")
                            : (encoding == ros::Encoding::cdr ? "sensor_msgs/msg/PointCloud2" : "sensor_msgs/PointCloud2");
  const std::string definition = encoding == ros::Encoding::cdr ? *ros::known_definition(type, encoding)
                                                                : (custom ? ros1_custom : ros1_cloud);
  std::optional<double> rate;
  if ((data[0] & 4u) != 0) rate = 200000.0;  // [Hz]
  ros::PointMessageDecoder decoder(type, definition, encoding, rate);
  const io::detail::BufferOrigin origin{"message", "payload byte ", 0};
  std::vector<ros::TimedPoint> points;
  streamclust::fuzz::only_throws<io::InputError>([&] { decoder.decode(data + 1, size - 1, origin, points); });
  return 0;
}
