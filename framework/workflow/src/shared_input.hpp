#pragma once
// The input of a fused attribute chain, fetched once per read of the chain's result.
//
// Why: the attributes of a chain read the input independently (chaos and envelope each ask for the
// block plus their own halo), so a generated (synthetic) or decoded (file) input would be produced
// once per attribute that reads it. SharedInput sits between the input and the attributes;
// PrefetchingResult wraps the chain's result. A read of box B of the result first fetches
// B grown by the chain's total halo (clipped to the cube) from the input, once, on the calling
// thread; every read of the input the attributes make inside that box is then a copy. Reads that
// fall outside it (a normalise step's percentile sample, an attribute that under-states its halo)
// go to the input directly. Values never depend on it: the input is box-independent.
//
// Memory: per thread reading the result, one fetched box (the block plus the halo); its storage
// stays for the thread's next fetch when the read ends, until the SharedInput goes.
//
// Thread safety: as the input's; each thread has its own fetched box.

#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "geotandem/volume/volume.hpp"

namespace geotandem::workflow::detail {

class SharedInput final : public volume::Volume {
public:
  explicit SharedInput(std::shared_ptr<const volume::Volume> input) : input_(std::move(input)) {}

  const volume::Geometry& geometry() const override { return input_->geometry(); }
  std::string format() const override { return input_->format(); }
  std::string source() const override { return input_->source(); }
  std::vector<volume::FormatDetail> format_details() const override { return input_->format_details(); }

  // Fetches `box` (inside the cube) for the calling thread's next reads; release() ends its use (the
  // storage is kept for the next fetch).
  void fetch(const volume::Box& box) const;
  void release() const;

  struct Counts {
    std::int64_t fetched = 0; // samples read from the input by fetch()
    std::int64_t served = 0;  // samples handed out from fetched boxes
    std::int64_t direct = 0;  // samples read from the input because no fetched box held them
  };
  Counts counts() const;

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  struct Fetched {
    volume::Box box{};
    std::vector<float> values;
  };
  Fetched& mine() const;

  std::shared_ptr<const volume::Volume> input_;
  mutable std::mutex mutex_;
  mutable std::map<std::thread::id, Fetched> fetched_;
  mutable Counts counts_;
};

// The input as a chain's attributes see it when the recipe fills missing samples (`input.nan:
// fill`): the input is opened with its missing samples (NaN or infinite) read as NaN, and here they
// read as 0, as a dead trace would. Filled with the lowest float, as the extraction wants them,
// they would swamp every filter that reaches them: an envelope of -3e38, a normalisation scale of
// infinity, a product of NaN.
class DeadSamples final : public volume::Volume {
public:
  explicit DeadSamples(std::shared_ptr<const volume::Volume> input) : input_(std::move(input)) {}

  const volume::Geometry& geometry() const override { return input_->geometry(); }
  std::string format() const override { return input_->format(); }
  std::string source() const override { return input_->source(); }
  std::vector<volume::FormatDetail> format_details() const override { return input_->format_details(); }

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  std::shared_ptr<const volume::Volume> input_;
};

class PrefetchingResult final : public volume::Volume {
public:
  // `result` is computed from `input` (through the attributes). With `mask_missing`, a sample whose
  // input is missing (not finite: see DeadSamples) reads as `mask` (the lowest float; the highest
  // for an extraction of the side below), outside every body, whatever the attributes made of the
  // dead samples there.
  PrefetchingResult(std::shared_ptr<const volume::Volume> result, std::shared_ptr<const SharedInput> input,
                    bool mask_missing = false, float mask = std::numeric_limits<float>::lowest());

  const volume::Geometry& geometry() const override { return result_->geometry(); }
  std::string format() const override { return result_->format(); }
  std::string source() const override { return result_->source(); }
  volume::Index3 source_halo() const override { return result_->source_halo(); }
  const SharedInput& input() const { return *input_; }

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  std::shared_ptr<const volume::Volume> result_;
  std::shared_ptr<const SharedInput> input_;
  bool mask_missing_;
  float mask_;
};

} // namespace geotandem::workflow::detail
