// The worker's I/O thread (worker_link.hpp).
#include "worker_link.hpp"

#include "transport_security.hpp"

#include "zmq_poll.hpp"

#include <unistd.h>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime::detail {

namespace {
const std::string kStop = std::string(1, '\0') + "stop"; // compute -> I/O
const std::string kGone = std::string(1, '\0') + "gone"; // I/O -> compute

bool is_control(const zmq::message_t& m, const std::string& what) {
  return m.size() == what.size() && std::memcmp(m.data(), what.data(), what.size()) == 0;
}

zmq::message_t frame_of(const Message& m) {
  const std::vector<std::byte> bytes = encode(m);
  return zmq::message_t(bytes.data(), bytes.size());
}
} // namespace

WorkerLink::WorkerLink(zmq::context_t& context, LinkOptions options, CancelToken cancel)
    : context_(context), options_(std::move(options)), cancel_(std::move(cancel)),
      inproc_("inproc://worker-link-" + std::to_string(getpid()) + "-" +
              std::to_string(reinterpret_cast<std::uintptr_t>(this))),
      pair_(context, zmq::socket_type::pair) {
  check_worker_keys(); // CURVE keys, when the manager gave a key file
  pair_.set(zmq::sockopt::linger, 0);
  pair_.connect(inproc_); // inproc connect before bind is fine since ZeroMQ 4
  io_ = std::thread([this] { io_loop(); });
}

WorkerLink::~WorkerLink() {
  try {
    pair_.send(zmq::buffer(kStop), zmq::send_flags::dontwait);
  } catch (const zmq::error_t&) {
  }
  if (io_.joinable()) io_.join();
}

void WorkerLink::send(const Message& message) {
  zmq::message_t frame = frame_of(message);
  bytes_sent_ += frame.size();
  pair_.send(frame, zmq::send_flags::none);
}

std::optional<Message> WorkerLink::receive(std::chrono::milliseconds timeout) {
  zmq::pollitem_t item{pair_.handle(), 0, ZMQ_POLLIN, 0};
  if (gone_) throw Error("the manager at " + options_.endpoint + " is gone", {.worker = options_.token});
  if (poll_items(&item, 1, timeout) == 0) return std::nullopt;
  zmq::message_t m;
  if (!pair_.recv(m, zmq::recv_flags::dontwait)) return std::nullopt;
  if (is_control(m, kGone))
    throw Error("the manager at " + options_.endpoint + " has been silent for " +
                    std::to_string(options_.manager_timeout.count() / 1000.0) + " s: it is gone",
                {.worker = options_.token}, "this worker stops; rerun the extraction to resume");
  return decode(std::span(static_cast<const std::byte*>(m.data()), m.size()), options_.max_message);
}

void WorkerLink::io_loop() {
  zmq::socket_t pair(context_, zmq::socket_type::pair), dealer(context_, zmq::socket_type::dealer);
  pair.set(zmq::sockopt::linger, 0);
  pair.bind(inproc_);
  dealer.set(zmq::sockopt::routing_id, options_.token);
  dealer.set(zmq::sockopt::linger, 1000); // a final message gets a second to leave
  dealer.set(zmq::sockopt::maxmsgsize, static_cast<std::int64_t>(options_.max_message));
  // After a dropped connection it reconnects under its token a second later (ZeroMQ's default is
  // 0.1 s): by then the manager has closed its end of the old one. Its ROUTER takes no routing-id
  // handover, and ignores a connection whose routing id is still held (manager_socket.cpp).
  dealer.set(zmq::sockopt::reconnect_ivl, 1000);
  secure_worker_socket(dealer); // CURVE when the manager's key file is given
  dealer.connect(options_.endpoint);
  using Clock = std::chrono::steady_clock;
  auto heard = Clock::now(), beat = Clock::now();
  Message heartbeat;
  heartbeat.kind = MessageKind::heartbeat;
  const std::vector<std::byte> beat_bytes = encode(heartbeat);
  zmq::pollitem_t items[] = {{pair.handle(), 0, ZMQ_POLLIN, 0}, {dealer.handle(), 0, ZMQ_POLLIN, 0}};
  for (;;) {
    poll_items(items, 2, options_.heartbeat / 2);
    if (items[0].revents & ZMQ_POLLIN) {
      zmq::message_t m;
      while (pair.recv(m, zmq::recv_flags::dontwait)) {
        if (is_control(m, kStop)) return;
        dealer.send(m, zmq::send_flags::none);
      }
    }
    if (items[1].revents & ZMQ_POLLIN) {
      zmq::message_t m;
      while (dealer.recv(m, zmq::recv_flags::dontwait)) {
        heard = Clock::now();
        // Heartbeats stop here; anything else (even a damaged frame) goes to the compute thread,
        // which decodes and judges it.
        if (m.size() == beat_bytes.size() && std::memcmp(m.data(), beat_bytes.data(), m.size()) == 0) continue;
        pair.send(m, zmq::send_flags::none);
      }
    }
    const auto now = Clock::now();
    if (now - beat >= options_.heartbeat) {
      dealer.send(zmq::buffer(beat_bytes), zmq::send_flags::dontwait);
      beat = now;
    }
    if (!gone_ && now - heard > options_.manager_timeout) {
      gone_ = true;
      cancel_.cancel();
      pair.send(zmq::buffer(kGone), zmq::send_flags::dontwait);
    }
  }
}

} // namespace geotandem::runtime::detail
