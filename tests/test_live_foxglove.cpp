// SPDX-License-Identifier: MIT
// The live view's Foxglove WebSocket pieces without a client: the wire format
// (tools/live/foxglove_protocol.hpp: Message Data framing, JSON operations,
// subprotocol choice), the server's listening, errors and counters
// (tools/live/foxglove_server.hpp), and the cycle's CDR payloads it publishes
// (tools/cli/foxglove_frames.hpp). The reference client's view is the CTest
// foxglove_live (tests/scripts/check_foxglove_live.mjs).
#include "cli/foxglove_frames.hpp"
#include "live/foxglove_protocol.hpp"
#include "live/foxglove_server.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

using namespace streamclust;
namespace fg = streamclust::live::foxglove;
using Json = nlohmann::json;

namespace {

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t b : bytes) s += {digits[b >> 4], digits[b & 15]};
  return s;
}

}  // namespace

TEST_CASE("foxglove Message Data: opcode, little-endian subscription id and log time, then the payload") {
  // The protocol's test vector: subscription 0, 123456789 ns, payload {"a":1}.
  const std::string payload = R"({"a":1})";
  const auto frame = fg::message_data_frame(0, 123456789, reinterpret_cast<const std::uint8_t*>(payload.data()),
                                            payload.size());
  CHECK(hex(frame) == "01" "00000000" "15cd5b0700000000" "7b2261223a317d");
  // Every byte of both fields in its place.
  const auto ordered = fg::message_data_frame(0x04030201u, 0x0c0b0a0908070605ull, nullptr, 0);
  CHECK(hex(ordered) == "01" "01020304" "05060708090a0b0c");
  CHECK(ordered.size() == fg::kMessageDataHeader);
}

TEST_CASE("foxglove subprotocol: either name, the client's first; none otherwise") {
  CHECK(fg::choose_subprotocol({"foxglove.websocket.v1"}) == "foxglove.websocket.v1");
  CHECK(fg::choose_subprotocol({"foxglove.sdk.v1"}) == "foxglove.sdk.v1");
  CHECK(fg::choose_subprotocol({"chat", "foxglove.sdk.v1", "foxglove.websocket.v1"}) == "foxglove.sdk.v1");
  CHECK(fg::choose_subprotocol({"foxglove.websocket.v2", "chat"}).empty());
  CHECK(fg::choose_subprotocol({}).empty());
}

TEST_CASE("foxglove server operations: serverInfo, advertise, unadvertise, status") {
  const Json info = Json::parse(fg::server_info_json("streamclust", "42"));
  CHECK(info["op"] == "serverInfo");
  CHECK(info["name"] == "streamclust");
  CHECK(info["capabilities"] == Json::array());
  CHECK(info["metadata"] == Json::object());
  CHECK(info["sessionId"] == "42");

  const Json ad = Json::parse(fg::advertise_json(
      {{3, "/streamclust/points", "cdr", "foxglove_msgs/msg/PointCloud", "float64 x\n", "ros2msg"}}));
  CHECK(ad["op"] == "advertise");
  REQUIRE(ad["channels"].size() == 1);
  const Json& c = ad["channels"][0];
  CHECK(c["id"] == 3);
  CHECK(c["topic"] == "/streamclust/points");
  CHECK(c["encoding"] == "cdr");
  CHECK(c["schemaName"] == "foxglove_msgs/msg/PointCloud");
  CHECK(c["schema"] == "float64 x\n");
  CHECK(c["schemaEncoding"] == "ros2msg");

  CHECK(Json::parse(fg::unadvertise_json({3, 5})) == Json{{"op", "unadvertise"}, {"channelIds", {3, 5}}});
  const Json warning = Json::parse(fg::status_json(fg::StatusLevel::warning, "slow", "drops"));
  CHECK(warning == Json{{"op", "status"}, {"level", 1}, {"message", "slow"}, {"id", "drops"}});
  CHECK(Json::parse(fg::status_json(fg::StatusLevel::error, "bad")).count("id") == 0);
}

TEST_CASE("foxglove client operations: subscribe and unsubscribe parsed, malformed ones named") {
  const auto sub = fg::parse_client_op(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":2},{"id":7,"channelId":4294967295}]})");
  CHECK(sub.kind == fg::ClientOp::Kind::subscribe);
  REQUIRE(sub.subscriptions.size() == 2);
  CHECK(sub.subscriptions[0] == std::pair<std::uint32_t, std::uint32_t>{0, 2});
  CHECK(sub.subscriptions[1] == std::pair<std::uint32_t, std::uint32_t>{7, 4294967295u});

  const auto unsub = fg::parse_client_op(R"({"op":"unsubscribe","subscriptionIds":[7,0]})");
  CHECK(unsub.kind == fg::ClientOp::Kind::unsubscribe);
  CHECK(unsub.unsubscriptions == std::vector<std::uint32_t>{7, 0});

  const auto other = fg::parse_client_op(R"({"op":"getParameters","parameterNames":[]})");
  CHECK(other.kind == fg::ClientOp::Kind::other);
  CHECK(other.op == "getParameters");

  CHECK_THROWS_WITH_AS(fg::parse_client_op("{op"), "client message: expected a JSON object", std::invalid_argument);
  CHECK_THROWS_WITH_AS(fg::parse_client_op(R"({"op":3})"), "client message: expected a string \"op\"",
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(fg::parse_client_op(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":-1}]})"),
                       "subscribe: subscriptions[0]: expected \"channelId\" as an integer in [0, 4294967295]",
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(fg::parse_client_op(R"({"op":"subscribe"})"),
                       "subscribe: expected an array \"subscriptions\"", std::invalid_argument);
  CHECK_THROWS_WITH_AS(fg::parse_client_op(R"({"op":"unsubscribe","subscriptionIds":["a"]})"),
                       "unsubscribe: subscriptionIds[0]: expected \"id\" as an integer in [0, 4294967295]",
                       std::invalid_argument);
}

TEST_CASE("foxglove server: an ephemeral port, bind errors naming address:port, publish without clients") {
  live::FoxgloveServer server({"127.0.0.1", 0, "streamclust", 1000});
  REQUIRE(server.port() != 0);

  const std::string taken = "127.0.0.1:" + std::to_string(server.port());
  try {
    live::FoxgloveServer second({"127.0.0.1", server.port(), "streamclust", 1000});
    FAIL("a second server listened on " << taken);
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find("cannot listen on " + taken + ": ") != std::string::npos);
    CHECK(what.find("in use") != std::string::npos);  // the OS reason
  }
  CHECK_THROWS_WITH_AS(live::FoxgloveServer({"localhost:1", 0, "x", 1000}),
                       doctest::Contains("\"localhost:1\" is not an IPv4 or IPv6 address"), std::invalid_argument);
  CHECK_THROWS_AS(live::FoxgloveServer({"127.0.0.1", 0, "x", 0}), std::invalid_argument);

  const std::uint32_t a = server.advertise({0, "/a", "cdr", "std_msgs/msg/String", "string data\n", "ros2msg"});
  const std::uint32_t b = server.advertise({0, "/b", "cdr", "std_msgs/msg/String", "string data\n", "ros2msg"});
  CHECK(a != b);
  const std::vector<std::uint8_t> bytes(600, 7);
  server.publish(a, 1, bytes.data(), bytes.size());
  server.publish(b, 2, bytes.data(), bytes.size());  // 1200 bytes may wait for the network thread: over 1000
  const std::string unknown = "foxglove server: publish on channel " + std::to_string(b + 1) +
                              ", which advertise() never returned";
  CHECK_THROWS_WITH_AS(server.publish(b + 1, 3, bytes.data(), bytes.size()), unknown.c_str(),
                       std::invalid_argument);
  const std::vector<std::uint8_t> big(1001, 7);
  server.publish(a, 4, big.data(), big.size());  // larger than the limit: never queued

  const auto s = server.stats();
  CHECK(s.clients == 0);
  CHECK(s.messages_published + s.publishes_dropped == 3);
  CHECK(s.publishes_dropped >= 1);
  CHECK(s.messages_sent == 0);
  CHECK(s.messages_dropped == 0);
  CHECK(s.bytes_sent == 0);
  CHECK(s.network_error.empty());
}

TEST_CASE("foxglove frames: the labelled window, its boxes and the raw points as CDR payloads") {
  std::vector<io::Record> window(3);
  window[0].x = 1.5f;
  window[0].intensity = 9;
  window[1].y = 2.5f;
  window[2].z = -1;
  const std::vector<std::int64_t> labels = {4, 4, cli::kGroundLabel};
  cli::FoxgloveFrames frames;
  frames.build(window, labels, 3'000'000'007ull);
  frames.build_raw(window, 3'000'000'007ull);

  // Encapsulation header (CDR little-endian), then the stamp: 3 s 7 ns.
  const std::vector<std::uint8_t>& cloud = frames.point_cloud();
  REQUIRE(cloud.size() > 4 + 8 + 3 * 20);
  CHECK(hex({cloud.begin(), cloud.begin() + 12}) == "00010000" "03000000" "07000000");
  // The data ends the message: three 20-byte points; the last is ground, brown.
  const std::uint8_t* last = cloud.data() + cloud.size() - 20;
  float z = 0;
  std::int32_t label = 0;
  std::memcpy(&z, last + 8, 4);
  std::memcpy(&label, last + 12, 4);
  CHECK(z == -1);
  CHECK(label == cli::kGroundLabel);
  CHECK(hex({last + 16, last + 20}) == "8c6946ff");

  // One box (label 4): its id "4" appears as a CDR string (length 2 with the NUL).
  const std::vector<std::uint8_t>& scene = frames.scene_update();
  const std::string id_text = std::string("\x02\x00\x00\x00", 4) + "4";
  CHECK(std::string(scene.begin(), scene.end()).find(id_text) != std::string::npos);

  // Raw: x y z intensity, 16 bytes a point, ending the message.
  const std::vector<std::uint8_t>& raw = frames.raw_cloud();
  float first[4] = {};
  std::memcpy(first, raw.data() + raw.size() - 3 * 16, 16);
  CHECK(first[0] == 1.5f);
  CHECK(first[3] == 9);
}
