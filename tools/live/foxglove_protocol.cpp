// SPDX-License-Identifier: MIT
#include "live/foxglove_protocol.hpp"

#include <nlohmann/json.hpp>

#include <cstring>
#include <limits>
#include <stdexcept>

namespace streamclust::live::foxglove {

namespace {

using Json = nlohmann::json;

/// The unsigned 32-bit value of `field` in `object`, or std::invalid_argument naming `where`.
std::uint32_t u32_field(const Json& object, const char* field, const std::string& where) {
  const auto it = object.find(field);
  if (it == object.end() || !it->is_number_integer() || it->get<std::int64_t>() < 0 ||
      it->get<std::int64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument(where + ": expected \"" + field + "\" as an integer in [0, 4294967295]");
  }
  return static_cast<std::uint32_t>(it->get<std::int64_t>());
}

}  // namespace

std::string choose_subprotocol(const std::vector<std::string>& offered) {
  for (const std::string& name : offered) {
    if (name == kSubprotocolV1 || name == kSubprotocolSdk) return name;
  }
  return {};
}

std::string server_info_json(const std::string& name, const std::string& session_id) {
  return Json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", Json::array()},
              {"metadata", Json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string advertise_json(const std::vector<Channel>& channels) {
  Json list = Json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return Json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids) {
  return Json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string status_json(StatusLevel level, const std::string& message, const std::string& id) {
  Json j{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}};
  if (!id.empty()) j["id"] = id;
  return j.dump();
}

void write_message_data_header(std::uint8_t* out, std::uint32_t subscription_id, std::uint64_t log_time_ns) {
  out[0] = 0x01;
  for (int i = 0; i < 4; ++i) out[1 + i] = static_cast<std::uint8_t>(subscription_id >> (8 * i));
  for (int i = 0; i < 8; ++i) out[5 + i] = static_cast<std::uint8_t>(log_time_ns >> (8 * i));
}

std::vector<std::uint8_t> message_data_frame(std::uint32_t subscription_id, std::uint64_t log_time_ns,
                                             const std::uint8_t* payload, std::size_t size) {
  std::vector<std::uint8_t> frame(kMessageDataHeader + size);
  write_message_data_header(frame.data(), subscription_id, log_time_ns);
  if (size > 0) std::memcpy(frame.data() + kMessageDataHeader, payload, size);
  return frame;
}

ClientOp parse_client_op(const std::string& text) {
  const Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) throw std::invalid_argument("client message: expected a JSON object");
  const auto op = j.find("op");
  if (op == j.end() || !op->is_string()) throw std::invalid_argument("client message: expected a string \"op\"");
  ClientOp parsed;
  parsed.op = op->get<std::string>();
  if (parsed.op == "subscribe") {
    parsed.kind = ClientOp::Kind::subscribe;
    const auto list = j.find("subscriptions");
    if (list == j.end() || !list->is_array()) throw std::invalid_argument("subscribe: expected an array \"subscriptions\"");
    for (std::size_t i = 0; i < list->size(); ++i) {
      const Json& s = (*list)[i];
      const std::string where = "subscribe: subscriptions[" + std::to_string(i) + "]";
      if (!s.is_object()) throw std::invalid_argument(where + ": expected an object");
      parsed.subscriptions.emplace_back(u32_field(s, "id", where), u32_field(s, "channelId", where));
    }
  } else if (parsed.op == "unsubscribe") {
    parsed.kind = ClientOp::Kind::unsubscribe;
    const auto list = j.find("subscriptionIds");
    if (list == j.end() || !list->is_array()) {
      throw std::invalid_argument("unsubscribe: expected an array \"subscriptionIds\"");
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
      const Json holder{{"id", (*list)[i]}};
      parsed.unsubscriptions.push_back(
          u32_field(holder, "id", "unsubscribe: subscriptionIds[" + std::to_string(i) + "]"));
    }
  }
  return parsed;
}

}  // namespace streamclust::live::foxglove
