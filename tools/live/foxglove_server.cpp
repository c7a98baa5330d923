// SPDX-License-Identifier: MIT
// The server behind live/foxglove_server.hpp. websocketpp 0.8.2 does not
// compile with g++ 12 at C++20, so this file is built at C++17 in its own
// library (tools/CMakeLists.txt) and its header shows no websocketpp type.
#include "live/foxglove_server.hpp"

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace streamclust::live {

namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Clock = std::chrono::steady_clock;

/// What the server keeps of one connected client (network thread only).
struct Client {
  WsServer::connection_ptr connection;
  std::map<std::uint32_t, std::uint32_t> subscription_of_channel;  // channel id -> the client's subscription id
  std::uint64_t dropped = 0;             // messages it lost to a full send buffer
  std::uint64_t dropped_unreported = 0;  // of which not yet told in a status
  Clock::time_point last_warning{};
};

/// "address:port", IPv6 addresses in brackets.
std::string endpoint_text(const std::string& address, std::uint16_t port) {
  const bool v6 = address.find(':') != std::string::npos;
  return (v6 ? "[" + address + "]" : address) + ":" + std::to_string(port);
}

constexpr auto kWarningInterval = std::chrono::seconds(1);  // at most one drop warning a second per client
constexpr auto kCloseGrace = std::chrono::seconds(1);       // shutdown: wait this long for closes to complete

}  // namespace

struct FoxgloveServer::Impl {
  Options options;
  WsServer server;
  std::thread network;
  std::uint16_t port = 0;
  std::string session_id;

  // Network thread only.
  std::map<websocketpp::connection_hdl, Client, std::owner_less<websocketpp::connection_hdl>> clients;
  std::map<std::uint32_t, foxglove::Channel> channels;

  // Any thread.
  std::atomic<std::uint32_t> next_channel_id{1};
  std::atomic<std::size_t> pending_bytes{0};  // [bytes] published, not yet handed to the clients
  std::atomic<std::size_t> client_count{0};
  std::atomic<std::uint64_t> published{0}, sent{0}, dropped{0}, publishes_dropped{0}, bytes_sent{0};
  std::mutex run_mutex;
  std::condition_variable run_done;
  bool finished = false;      // guarded by run_mutex: the network thread has left run()
  std::string network_error;  // guarded by run_mutex: the exception that ended run() early

  explicit Impl(Options o) : options(std::move(o)) {}

  void start() {
    if (options.send_buffer_limit == 0) {
      throw std::invalid_argument("foxglove server: send_buffer_limit must be at least 1 byte");
    }
    asio::error_code address_error;
    const asio::ip::address address = asio::ip::make_address(options.address, address_error);
    if (address_error) {
      throw std::invalid_argument("foxglove server: \"" + options.address +
                                  "\" is not an IPv4 or IPv6 address (expected e.g. 127.0.0.1, 0.0.0.0 or ::1)");
    }
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    server.init_asio();
    server.set_reuse_addr(true);
    server.set_validate_handler([this](websocketpp::connection_hdl h) { return validate(h); });
    server.set_open_handler([this](websocketpp::connection_hdl h) { on_open(h); });
    server.set_close_handler([this](websocketpp::connection_hdl h) { on_close(h); });
    server.set_message_handler([this](websocketpp::connection_hdl h, WsServer::message_ptr m) { on_message(h, m); });

    std::error_code ec;
    server.listen(asio::ip::tcp::endpoint(address, options.port), ec);
    if (!ec) server.start_accept(ec);
    if (ec) {
      throw std::runtime_error("foxglove server: cannot listen on " + endpoint_text(options.address, options.port) +
                               ": " + ec.message());
    }
    port = server.get_local_endpoint(ec).port();
    session_id = std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
    network = std::thread([this] { run(); });
  }

  /// The network thread. An exception stops it; publish() keeps returning at
  /// once and stats() reports the error.
  void run() {
    std::string error;
    try {
      server.run();
    } catch (const std::exception& e) {
      error = std::string("foxglove server: the network thread stopped: ") + e.what();
    }
    const std::lock_guard<std::mutex> lock(run_mutex);
    finished = true;
    network_error = std::move(error);
    run_done.notify_all();
  }

  void shut_down() {
    asio::post(server.get_io_service(), [this] {
      std::error_code ec;
      server.stop_listening(ec);
      for (auto& [handle, client] : clients) {
        client.connection->close(websocketpp::close::status::going_away, "server shutting down", ec);
      }
    });
    {
      std::unique_lock<std::mutex> lock(run_mutex);
      run_done.wait_for(lock, kCloseGrace, [this] { return finished; });
    }
    server.stop();  // a client that never reads cannot complete its close
    network.join();
  }

  /// Accepts a handshake offering one of the protocol's subprotocols and answers with it; else 400.
  bool validate(websocketpp::connection_hdl handle) {
    const WsServer::connection_ptr con = server.get_con_from_hdl(handle);
    const std::string chosen = foxglove::choose_subprotocol(con->get_requested_subprotocols());
    if (chosen.empty()) {
      con->set_status(websocketpp::http::status_code::bad_request);
      con->set_body(std::string("expected the WebSocket subprotocol ") + foxglove::kSubprotocolV1 + " or " +
                    foxglove::kSubprotocolSdk + "\n");
      return false;
    }
    con->select_subprotocol(chosen);
    return true;
  }

  void on_open(websocketpp::connection_hdl handle) {
    Client& client = clients[handle];
    client.connection = server.get_con_from_hdl(handle);
    client_count = clients.size();
    send_text(client, foxglove::server_info_json(options.name, session_id));
    if (channels.empty()) return;
    std::vector<foxglove::Channel> all;
    for (const auto& [id, channel] : channels) all.push_back(channel);
    send_text(client, foxglove::advertise_json(all));
  }

  void on_close(websocketpp::connection_hdl handle) {
    clients.erase(handle);
    client_count = clients.size();
  }

  void on_message(websocketpp::connection_hdl handle, const WsServer::message_ptr& message) {
    const auto it = clients.find(handle);
    if (it == clients.end()) return;
    Client& client = it->second;
    if (message->get_opcode() != websocketpp::frame::opcode::text) {
      send_text(client, foxglove::status_json(foxglove::StatusLevel::error,
                                              "binary client messages are not supported (no clientPublish)"));
      return;
    }
    try {
      const foxglove::ClientOp op = foxglove::parse_client_op(message->get_payload());
      if (op.kind == foxglove::ClientOp::Kind::subscribe) {
        for (const auto& [subscription, channel] : op.subscriptions) subscribe(client, subscription, channel);
      } else if (op.kind == foxglove::ClientOp::Kind::unsubscribe) {
        for (const std::uint32_t subscription : op.unsubscriptions) {
          for (auto s = client.subscription_of_channel.begin(); s != client.subscription_of_channel.end();) {
            s = s->second == subscription ? client.subscription_of_channel.erase(s) : std::next(s);
          }
        }
      } else {
        send_text(client, foxglove::status_json(foxglove::StatusLevel::warning,
                                                "operation \"" + op.op + "\" is not supported by this server"));
      }
    } catch (const std::invalid_argument& e) {
      send_text(client, foxglove::status_json(foxglove::StatusLevel::error, e.what()));
    }
  }

  void subscribe(Client& client, std::uint32_t subscription, std::uint32_t channel) {
    std::string problem;
    if (channels.count(channel) == 0) {
      problem = "subscribe: no channel " + std::to_string(channel);
    } else if (client.subscription_of_channel.count(channel) != 0) {
      problem = "subscribe: channel " + std::to_string(channel) + " is already subscribed";
    } else {
      for (const auto& [c, s] : client.subscription_of_channel) {
        if (s == subscription) problem = "subscribe: subscription id " + std::to_string(s) + " is already in use";
      }
    }
    if (problem.empty()) {
      client.subscription_of_channel[channel] = subscription;
    } else {
      send_text(client, foxglove::status_json(foxglove::StatusLevel::warning, problem));
    }
  }

  /// Control text: always queued (small; sent once per connection or per change).
  void send_text(Client& client, const std::string& text) {
    client.connection->send(text, websocketpp::frame::opcode::text);  // an error: the connection is closing
  }

  /// One message to every subscriber of `channel`, or counted as dropped for
  /// those whose send buffer it would overfill. O(clients + size per subscriber).
  void deliver(std::uint32_t channel, std::uint64_t log_time_ns, const std::vector<std::uint8_t>& payload) {
    const std::size_t frame_size = foxglove::kMessageDataHeader + payload.size();
    for (auto& [handle, client] : clients) {
      const auto subscription = client.subscription_of_channel.find(channel);
      if (subscription == client.subscription_of_channel.end()) continue;
      if (client.connection->get_buffered_amount() + frame_size > options.send_buffer_limit) {
        ++client.dropped;
        ++client.dropped_unreported;
        ++dropped;
        warn_dropped(client);
        continue;
      }
      std::uint8_t header[foxglove::kMessageDataHeader];
      foxglove::write_message_data_header(header, subscription->second, log_time_ns);
      const WsServer::message_ptr frame =
          client.connection->get_message(websocketpp::frame::opcode::binary, frame_size);
      frame->set_payload(header, sizeof header);
      frame->append_payload(payload.data(), payload.size());
      if (!client.connection->send(frame)) {
        ++sent;
        bytes_sent += frame_size;
      }
    }
  }

  /// A warning status to a client that lost messages, at most once per
  /// kWarningInterval and only when it fits in its send buffer.
  void warn_dropped(Client& client) {
    const Clock::time_point now = Clock::now();
    if (now - client.last_warning < kWarningInterval) return;
    const std::string text = foxglove::status_json(
        foxglove::StatusLevel::warning,
        "dropped " + std::to_string(client.dropped_unreported) + " messages (" + std::to_string(client.dropped) +
            " in all): this client reads slower than the server publishes (send buffer full at " +
            std::to_string(options.send_buffer_limit) + " bytes)",
        "streamclust.dropped");
    if (client.connection->get_buffered_amount() + text.size() > options.send_buffer_limit) return;
    send_text(client, text);
    client.dropped_unreported = 0;
    client.last_warning = now;
  }
};

FoxgloveServer::FoxgloveServer(Options options) : impl_(std::make_unique<Impl>(std::move(options))) {
  impl_->start();
}

FoxgloveServer::~FoxgloveServer() { impl_->shut_down(); }

std::uint16_t FoxgloveServer::port() const { return impl_->port; }

std::uint32_t FoxgloveServer::advertise(foxglove::Channel channel) {
  channel.id = impl_->next_channel_id++;
  const std::uint32_t id = channel.id;
  Impl* impl = impl_.get();
  asio::post(impl->server.get_io_service(), [impl, channel = std::move(channel)] {
    impl->channels[channel.id] = channel;
    const std::string text = foxglove::advertise_json({channel});
    for (auto& [handle, client] : impl->clients) impl->send_text(client, text);
  });
  return id;
}

void FoxgloveServer::unadvertise(std::uint32_t channel_id) {
  Impl* impl = impl_.get();
  asio::post(impl->server.get_io_service(), [impl, channel_id] {
    if (impl->channels.erase(channel_id) == 0) return;
    const std::string text = foxglove::unadvertise_json({channel_id});
    for (auto& [handle, client] : impl->clients) {
      client.subscription_of_channel.erase(channel_id);
      impl->send_text(client, text);
    }
  });
}

void FoxgloveServer::publish(std::uint32_t channel_id, std::uint64_t log_time_ns, const std::uint8_t* data,
                             std::size_t size) {
  Impl* impl = impl_.get();
  if (channel_id == 0 || channel_id >= impl->next_channel_id.load()) {
    throw std::invalid_argument("foxglove server: publish on channel " + std::to_string(channel_id) +
                                ", which advertise() never returned");
  }
  std::size_t pending = impl->pending_bytes.load();
  do {
    if (pending + size > impl->options.send_buffer_limit) {
      ++impl->publishes_dropped;
      return;
    }
  } while (!impl->pending_bytes.compare_exchange_weak(pending, pending + size));
  auto payload = std::make_shared<const std::vector<std::uint8_t>>(data, data + size);
  ++impl->published;
  asio::post(impl->server.get_io_service(), [impl, channel_id, log_time_ns, payload] {
    impl->deliver(channel_id, log_time_ns, *payload);
    impl->pending_bytes -= payload->size();
  });
}

FoxgloveServer::Stats FoxgloveServer::stats() const {
  Stats s;
  s.clients = impl_->client_count.load();
  s.messages_published = impl_->published.load();
  s.messages_sent = impl_->sent.load();
  s.messages_dropped = impl_->dropped.load();
  s.publishes_dropped = impl_->publishes_dropped.load();
  s.bytes_sent = impl_->bytes_sent.load();
  const std::lock_guard<std::mutex> lock(impl_->run_mutex);
  s.network_error = impl_->network_error;
  return s;
}

}  // namespace streamclust::live
