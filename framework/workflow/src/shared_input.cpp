#include "shared_input.hpp"

#include <cmath>
#include <limits>

namespace geotandem::workflow::detail {

SharedInput::Fetched& SharedInput::mine() const {
  std::lock_guard lock(mutex_);
  return fetched_[std::this_thread::get_id()]; // map nodes stay put: the reference outlives the lock
}

void SharedInput::fetch(const volume::Box& box) const {
  Fetched& f = mine();
  f.box = volume::Box{};
  f.values.resize(static_cast<std::size_t>(box.count()));
  input_->read(box, f.values);
  f.box = box;
  std::lock_guard lock(mutex_);
  counts_.fetched += box.count();
}

void SharedInput::release() const {
  Fetched& f = mine();
  // The storage stays for the thread's next fetch: the next block's box is about as large, and
  // pages already faulted in cost nothing to fill again (giving them back made the kernel zero a
  // fresh box's worth for every block).
  f.box = volume::Box{};
}

SharedInput::Counts SharedInput::counts() const {
  std::lock_guard lock(mutex_);
  return counts_;
}

void SharedInput::read_box(const volume::Box& box, std::span<float> out) const {
  const Fetched& f = mine();
  if (!f.box.empty() && f.box.contains(box)) {
    volume::copy_region(f.values.data(), f.box, out.data(), box, box);
    std::lock_guard lock(mutex_);
    counts_.served += box.count();
    return;
  }
  input_->read(box, out);
  std::lock_guard lock(mutex_);
  counts_.direct += box.count();
}

void DeadSamples::read_box(const volume::Box& box, std::span<float> out) const {
  input_->read(box, out);
  for (float& v : out)
    if (!std::isfinite(v)) v = 0.0f;
}

PrefetchingResult::PrefetchingResult(std::shared_ptr<const volume::Volume> result,
                                     std::shared_ptr<const SharedInput> input, bool mask_missing, float mask)
    : result_(std::move(result)), input_(std::move(input)), mask_missing_(mask_missing), mask_(mask) {}

void PrefetchingResult::read_box(const volume::Box& box, std::span<float> out) const {
  const volume::Box wanted = box.grown(result_->source_halo()).intersection(geometry().bounds());
  input_->fetch(wanted);
  try {
    result_->read(box, out);
    if (mask_missing_) {
      thread_local std::vector<float> in;
      in.resize(static_cast<std::size_t>(box.count()));
      input_->read(box, in); // inside the fetched box: a copy
      for (std::size_t n = 0; n < in.size(); ++n)
        if (!std::isfinite(in[n])) out[n] = mask_;
    }
  } catch (...) {
    input_->release();
    throw;
  }
  input_->release();
}

} // namespace geotandem::workflow::detail
