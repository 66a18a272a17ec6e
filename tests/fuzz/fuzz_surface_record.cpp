// libFuzzer target: the working-surface record decoder and the merge of a record (issue 52: a
// record with valid checksums but forged content crashed the worker that merged it). Each input is
// tried as it is (the header's checks), then resealed, its length and XXH64 made right so that the
// mutations reach the content as a forger's would: decoded alone (deserialize) and merged into a
// real surface (merge_record), and every surface that takes it in is finished. A refusal must be a
// geotandem error; anything else (a crash, a sanitizer report, another exception) is a finding.

#include <xxhash.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "geotandem/core/error.hpp"
#include "surface_records.hpp"

using namespace geotandem;

namespace {

void try_record(const std::vector<std::byte>& record) {
  try {
    tandem::WorkingSurface alone = tandem::deserialize(record, nullptr);
    alone.finish();
  } catch (const Error&) {
  }
  static const std::vector<std::byte> receiver = fuzz::surface_records().receiver;
  try {
    tandem::WorkingSurface into = tandem::deserialize(receiver, nullptr);
    tandem::merge_record(into, record);
    into.finish();
  } catch (const Error&) {
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::byte> record(size);
  if (size > 0) std::memcpy(record.data(), data, size);
  try_record(record);
  if (size >= tandem::kSurfaceWireHeaderSize) {
    const std::uint64_t length = size - tandem::kSurfaceWireHeaderSize;
    const std::uint64_t hash = XXH64(record.data() + tandem::kSurfaceWireHeaderSize, length, 0);
    std::memcpy(record.data() + 16, &length, 8);
    std::memcpy(record.data() + 24, &hash, 8);
    try_record(record);
  }
  return 0;
}
