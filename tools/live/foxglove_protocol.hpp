// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The wire format of the Foxglove WebSocket protocol v1 (subprotocols
/// `foxglove.websocket.v1` and `foxglove.sdk.v1`, identical but for the name):
/// the JSON text operations a server sends and receives, and the binary
/// Message Data frame. Pure functions over strings and bytes: no network, so
/// they are tested without a client. Thread-safe (no shared state).
///
/// | op | direction | fields |
/// |---|---|---|
/// | `serverInfo` | server to client | `name`, `capabilities` [], `metadata` {}, `sessionId` |
/// | `advertise` | server to client | `channels` [{`id`, `topic`, `encoding`, `schemaName`, `schema`, `schemaEncoding`}] |
/// | `unadvertise` | server to client | `channelIds` [] |
/// | `status` | server to client | `level` (0 info, 1 warning, 2 error), `message`, optional `id` |
/// | `subscribe` | client to server | `subscriptions` [{`id` (the client's), `channelId`}] |
/// | `unsubscribe` | client to server | `subscriptionIds` [] |
///
/// Message Data (binary, little-endian): `0x01 | u32 subscription id | u64 log time [ns] | payload`.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace streamclust::live::foxglove {

/// The subprotocol names a server accepts, in its order of preference.
inline constexpr const char* kSubprotocolV1 = "foxglove.websocket.v1";
inline constexpr const char* kSubprotocolSdk = "foxglove.sdk.v1";

/// The subprotocol to answer a client that offers `offered` (in its order):
/// the first one it offers that the server speaks; empty when none (refuse).
std::string choose_subprotocol(const std::vector<std::string>& offered);

/// One advertised topic. `schema` is text (ros2msg for `cdr` channels).
struct Channel {
  std::uint32_t id = 0;
  std::string topic;           ///< e.g. `/streamclust/points`
  std::string encoding;        ///< message encoding, e.g. `cdr`
  std::string schema_name;     ///< e.g. `foxglove_msgs/msg/PointCloud`
  std::string schema;          ///< the schema text
  std::string schema_encoding; ///< e.g. `ros2msg`
};

/// Severity of a `status` operation.
enum class StatusLevel : int { info = 0, warning = 1, error = 2 };

std::string server_info_json(const std::string& name, const std::string& session_id);
std::string advertise_json(const std::vector<Channel>& channels);
std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids);
/// `id` empty: no id field (the message does not replace an earlier one).
std::string status_json(StatusLevel level, const std::string& message, const std::string& id = {});

/// Size [bytes] of a Message Data header (opcode, subscription id, log time).
inline constexpr std::size_t kMessageDataHeader = 13;

/// Writes a Message Data header (the payload follows it) into `out[0, kMessageDataHeader)`.
void write_message_data_header(std::uint8_t* out, std::uint32_t subscription_id, std::uint64_t log_time_ns);

/// A whole Message Data frame: header then `size` bytes of `payload`. O(size).
std::vector<std::uint8_t> message_data_frame(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                                             const std::uint8_t* payload, std::size_t size);

/// A client's text operation, parsed.
struct ClientOp {
  enum class Kind { subscribe, unsubscribe, other };
  Kind kind = Kind::other;
  std::string op;  ///< the `op` field as sent
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  ///< (subscription id, channel id)
  std::vector<std::uint32_t> unsubscriptions;                          ///< subscription ids
};

/// Parses one text frame from a client. Throws std::invalid_argument saying
/// what was expected where when it is not JSON, has no string `op`, or a
/// subscribe/unsubscribe has missing or out-of-range fields.
ClientOp parse_client_op(const std::string& text);

}  // namespace streamclust::live::foxglove
