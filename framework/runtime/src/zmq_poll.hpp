#pragma once
// zmq::poll that returns 0 instead of throwing when a signal interrupts it (Ctrl-C, SIGTERM): the
// caller's loop then checks its cancel token. Internal to the runtime.
#include <chrono>
#include <zmq.hpp>

namespace geotandem::runtime::detail {

inline int poll_items(zmq::pollitem_t* items, std::size_t n, std::chrono::milliseconds timeout) {
  try {
    return zmq::poll(items, n, timeout);
  } catch (const zmq::error_t& e) {
    if (e.num() == EINTR) {
      for (std::size_t i = 0; i < n; ++i)
        items[i].revents = 0;
      return 0;
    }
    throw;
  }
}

} // namespace geotandem::runtime::detail
