#pragma once
// The worker's connection to its manager: an I/O thread owns the DEALER socket (routing id: the
// launch token), sends heartbeats while the compute thread works, and declares the manager gone
// when it has been silent too long (then cancels the compute thread's task). The compute thread
// talks to it through an inproc PAIR socket of its own. Internal to the runtime.
#include <atomic>
#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <zmq.hpp>

#include "geotandem/core/cancel.hpp"
#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime::detail {

struct LinkOptions {
  std::string endpoint;
  std::string token;
  std::chrono::milliseconds heartbeat{500};
  std::chrono::milliseconds manager_timeout{10000};
  std::size_t max_message = kDefaultMaxMessage;
};

class WorkerLink {
public:
  // Call from the compute thread. `cancel` is cancelled when the manager is gone.
  WorkerLink(zmq::context_t& context, LinkOptions options, CancelToken cancel);
  ~WorkerLink(); // stops and joins the I/O thread
  WorkerLink(const WorkerLink&) = delete;
  WorkerLink& operator=(const WorkerLink&) = delete;

  void send(const Message& message);
  // The next message from the manager (heartbeats are handled by the link), or nullopt after
  // `timeout`. Throws Error when the manager is gone.
  std::optional<Message> receive(std::chrono::milliseconds timeout);
  std::uint64_t bytes_sent() const { return bytes_sent_.load(); }
  // True once the manager has been silent for the manager timeout (the link then cancelled).
  bool gone() const { return gone_.load(); }
  const std::string& endpoint() const { return options_.endpoint; }
  std::chrono::milliseconds manager_timeout() const { return options_.manager_timeout; }

private:
  void io_loop();

  zmq::context_t& context_;
  LinkOptions options_;
  CancelToken cancel_;
  std::string inproc_;
  zmq::socket_t pair_; // the compute thread's end
  std::atomic<bool> gone_{false};
  std::atomic<std::uint64_t> bytes_sent_{0};
  std::thread io_;
};

} // namespace geotandem::runtime::detail
