#pragma once
// Cooperative cancellation. Long operations take a const CancelToken& and call
// throw_if_cancelled() at safe points (between layers, blocks, components).

#include <atomic>
#include <memory>

#include "geotandem/core/error.hpp"

namespace geotandem {

class CancelToken {
public:
  CancelToken() : flag_(std::make_shared<std::atomic<bool>>(false)) {}

  // Thread- and signal-safe: only stores to a lock-free atomic.
  void cancel() const noexcept { flag_->store(true, std::memory_order_relaxed); }
  bool cancelled() const noexcept { return flag_->load(std::memory_order_relaxed); }
  // Throws geotandem::Cancelled once cancel() was called on this token or a copy of it.
  void throw_if_cancelled() const {
    if (cancelled()) throw Cancelled();
  }
  // The raw flag, for a signal handler that may not touch anything else.
  std::atomic<bool>* raw_flag() const noexcept { return flag_.get(); }

private:
  std::shared_ptr<std::atomic<bool>> flag_;
};

} // namespace geotandem
