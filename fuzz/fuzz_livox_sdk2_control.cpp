// SPDX-License-Identifier: MIT
// Fuzz target: one Livox SDK2 control datagram (live/sdk2_control.hpp),
// decoded as it comes and once more with its two CRCs made right (so that
// mutations reach the payload parsers), then encoded again.
//
// A bug, besides a crash, undefined behaviour, a leak or an exception: a
// frame that decodes and does not encode back to its bytes (the reserved
// bytes aside: the encoder writes zeros, and so another header CRC); a
// resealed frame refused for a CRC; a discovery ACK, 0x0100 ACK or 0x0100
// request whose parsed message does not encode back to the same payload
// (the request's reserved u16 aside); a parameter list whose pairs overlap,
// leave the payload or do not end it.

#include "support/expect.hpp"

#include <streamclust/live/sdk2_control.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace {

namespace live = streamclust::live;
using streamclust::fuzz::never_throws;
using streamclust::fuzz::require;

/// `b` with its reserved bytes zeroed and its header CRC recomputed.
std::vector<std::uint8_t> canonical(std::vector<std::uint8_t> b) {
  std::memset(b.data() + 12, 0, 6);
  const std::uint16_t crc = live::crc16_ccitt_false(b.data(), 18);
  std::memcpy(b.data() + 18, &crc, 2);
  return b;
}

/// `b` with both CRCs made right, where its length field allows.
std::vector<std::uint8_t> resealed(std::vector<std::uint8_t> b) {
  if (b.size() < live::sdk2_control_header_bytes) return b;
  const std::uint16_t length = static_cast<std::uint16_t>(b[2] | b[3] << 8);
  if (length >= live::sdk2_control_header_bytes && length <= b.size()) {
    const std::uint32_t crc32 = live::crc32_iso_hdlc(b.data() + 24, length - 24u);
    std::memcpy(b.data() + 20, &crc32, 4);
  }
  const std::uint16_t crc16 = live::crc16_ccitt_false(b.data(), 18);
  std::memcpy(b.data() + 18, &crc16, 2);
  return b;
}

void check_messages(const live::Sdk2ControlFrame& f) {
  std::vector<std::uint8_t> frame;
  live::Sdk2ControlFrame g;
  live::Sdk2DiscoveryAck discovery;
  if (live::parse_sdk2_discovery_ack(f, discovery)) {
    (void)live::sdk2_serial(discovery);
    (void)live::sdk2_device_name(discovery.dev_type);
    never_throws([&] { live::encode_sdk2_discovery_ack(f.seq, discovery, frame); });
    require(live::decode_sdk2_control(frame.data(), frame.size(), g) == live::Sdk2ControlStatus::ok &&
                g.data_size == f.data_size && std::memcmp(g.data, f.data, f.data_size) == 0,
            "a discovery ACK encodes back to its payload");
  }
  live::Sdk2SetParametersAck ack;
  if (live::parse_sdk2_set_parameters_ack(f, ack)) {
    never_throws([&] { live::encode_sdk2_set_parameters_ack(f.seq, ack, frame); });
    require(live::decode_sdk2_control(frame.data(), frame.size(), g) == live::Sdk2ControlStatus::ok &&
                g.data_size == f.data_size && std::memcmp(g.data, f.data, f.data_size) == 0,
            "a 0x0100 ACK encodes back to its payload");
  }
  if (f.cmd_id != live::sdk2_cmd_set_parameters || f.cmd_type != live::Sdk2CommandType::request) return;
  std::vector<live::Sdk2KeyValue> pairs;
  live::Sdk2ParameterStatus status{};
  never_throws([&] { status = live::parse_sdk2_parameters(f.data, f.data_size, pairs); });
  if (status != live::Sdk2ParameterStatus::ok) {
    require(status != live::Sdk2ParameterStatus::truncated || f.data_size < 4, "truncated means under 4 bytes");
    return;
  }
  const std::uint8_t* at = f.data + 4;
  live::Sdk2ParameterList list;
  for (const live::Sdk2KeyValue& kv : pairs) {
    require(kv.value == at + 4 && kv.value + kv.size <= f.data + f.data_size,
            "pairs follow each other within the payload");
    at = kv.value + kv.size;
    live::Sdk2HostIpInfo info;
    std::uint8_t u8 = 0;
    require(live::parse_sdk2_destination(kv, info) == (kv.size == 8), "a destination is 8 bytes");
    require(live::parse_sdk2_u8(kv, u8) == (kv.size == 1), "a byte value is 1 byte");
    never_throws([&] { list.add(kv.key, kv.value, kv.size); });
  }
  require(at == f.data + f.data_size, "the last pair ends the payload");
  require(list.bytes().size() == f.data_size && list.count() == pairs.size() &&
              std::memcmp(list.bytes().data(), f.data, 2) == 0 &&
              std::memcmp(list.bytes().data() + 4, f.data + 4, f.data_size - 4) == 0,
          "a parameter list encodes back to its payload");
}

/// Decodes `b`; for a frame, checks the round trip and the messages. Returns the status.
live::Sdk2ControlStatus check(const std::vector<std::uint8_t>& b) {
  live::Sdk2ControlFrame f;
  const live::Sdk2ControlStatus status = live::decode_sdk2_control(b.data(), b.size(), f);
  (void)live::describe(status);
  if (status != live::Sdk2ControlStatus::ok) return status;
  require(f.data == b.data() + 24 && f.data_size == b.size() - 24, "the data is the rest of the datagram");
  std::vector<std::uint8_t> frame;
  never_throws([&] { live::encode_sdk2_control(f, frame); });
  require(frame == canonical(b), "a frame encodes back to its bytes");
  check_messages(f);
  return status;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);  // its own allocation: ASan sees reads past it
  check(bytes);
  const live::Sdk2ControlStatus status = check(resealed(bytes));
  require(status != live::Sdk2ControlStatus::bad_header_crc && status != live::Sdk2ControlStatus::bad_data_crc,
          "a resealed frame passes its CRCs");
  return 0;
}
