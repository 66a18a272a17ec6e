#pragma once
// The manager's end of the transport: the ZeroMQ context and the ROUTER socket, created, set up
// and bound in one place (make_router), frames in and out, byte counts. Everything about the
// wire's framing (routing id first, one body frame) is checked here; what a body means is the
// manager's business. Internal to the runtime.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "geotandem/core/log.hpp"
#include "transport_security.hpp"

namespace geotandem::runtime::detail {

class ManagerSocket {
public:
  // Binds `bind` ("tcp://127.0.0.1:*" picks a free port). The socket is a CURVE server with this
  // run's keys written under `key_dir` (transport_security.hpp), on loopback too. Throws IoError
  // when it cannot bind or write the keys.
  ManagerSocket(const std::string& bind, std::size_t max_message, const std::string& key_dir, Logger& log);

  const std::string& endpoint() const { return endpoint_; }
  // Sends one message to the worker whose routing id is `token`; false when it cannot be reached
  // (gone, or its queue is full).
  bool send(const std::string& token, std::span<const std::byte> body);
  // Waits up to `timeout` for messages, then hands each well-framed one to `on_message` (token,
  // body); badly framed ones go to `on_bad` with the reason.
  void receive(std::chrono::milliseconds timeout,
               const std::function<void(const std::string&, std::span<const std::byte>)>& on_message,
               const std::function<void(const std::string&)>& on_bad);

  std::uint64_t bytes_in() const { return bytes_in_; }
  std::uint64_t bytes_out() const { return bytes_out_; }

private:
  zmq::context_t context_{1};
  zmq::socket_t router_;
  // CURVE and its ZAP handler. Declared after router_: it stops the socket's monitor
  // when destroyed, so it must go before the socket does.
  std::shared_ptr<ServerSecurity> security_;
  std::string endpoint_;
  Logger& log_;
  std::uint64_t bytes_in_ = 0, bytes_out_ = 0;
};

} // namespace geotandem::runtime::detail
