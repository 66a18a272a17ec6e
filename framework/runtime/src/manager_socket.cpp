// The manager's ROUTER socket (manager_socket.hpp).
#include "manager_socket.hpp"

#include "geotandem/core/error.hpp"
#include "zmq_poll.hpp"

namespace geotandem::runtime::detail {

namespace {

// Every socket option of the manager's socket in one place (its security and bind follow).
zmq::socket_t make_router(zmq::context_t& context, std::size_t max_message) {
  zmq::socket_t router(context, zmq::socket_type::router);
  router.set(zmq::sockopt::linger, 0);
  router.set(zmq::sockopt::router_mandatory, 1);
  // No routing-id handover: a second connection under a worker's token never takes its place.
  // (The token is no secret: it is in the worker's command line. CURVE keeps strangers out; this
  // keeps a confused or duplicated peer of the run's own from stealing another's messages.) A
  // worker whose connection drops reconnects under its token a second later (worker_link.cpp),
  // once this end of the old one is closed; a connection under a token still held is ignored.
  router.set(zmq::sockopt::router_handover, 0);
  router.set(zmq::sockopt::maxmsgsize, static_cast<std::int64_t>(max_message));
  return router;
}

} // namespace

ManagerSocket::ManagerSocket(const std::string& bind, std::size_t max_message, const std::string& key_dir, Logger& log)
    : router_(make_router(context_, max_message)), log_(log) {
  security_ = secure_manager_socket(context_, router_, bind, key_dir, log);
  try {
    router_.bind(bind);
  } catch (const zmq::error_t& e) {
    throw IoError("cannot listen on " + bind + ": " + e.what(), {}, "choose another address or port");
  }
  endpoint_ = router_.get(zmq::sockopt::last_endpoint);
}

bool ManagerSocket::send(const std::string& token, std::span<const std::byte> body) {
  try {
    router_.send(zmq::buffer(token), zmq::send_flags::sndmore);
    router_.send(zmq::buffer(body.data(), body.size()), zmq::send_flags::none);
    bytes_out_ += body.size();
    return true;
  } catch (const zmq::error_t& e) {
    log_.debug("cannot reach worker " + token + ": " + e.what());
    return false;
  }
}

void ManagerSocket::receive(std::chrono::milliseconds timeout,
                            const std::function<void(const std::string&, std::span<const std::byte>)>& on_message,
                            const std::function<void(const std::string&)>& on_bad) {
  zmq::pollitem_t item{router_.handle(), 0, ZMQ_POLLIN, 0};
  poll_items(&item, 1, timeout);
  zmq::message_t id, body;
  while (router_.recv(id, zmq::recv_flags::dontwait)) {
    if (!id.more()) {
      on_bad("a frame without a routing id");
      continue;
    }
    (void)router_.recv(body, zmq::recv_flags::none);
    // Extra frames from a foreign peer: read and drop them.
    bool extra = false;
    while (body.more()) {
      zmq::message_t rest;
      (void)router_.recv(rest, zmq::recv_flags::none);
      extra = true;
      body.swap(rest);
    }
    if (extra) {
      on_bad("a message of more than one frame");
      continue;
    }
    bytes_in_ += body.size();
    on_message(id.to_string(), std::span(static_cast<const std::byte*>(body.data()), body.size()));
  }
}

} // namespace geotandem::runtime::detail
