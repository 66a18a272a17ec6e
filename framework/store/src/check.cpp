#include "geotandem/store/check.hpp"

#include <chrono>

#include "geotandem/core/error.hpp"

namespace geotandem::store {

std::optional<std::string> verify_component(const ComponentStore& store, const ComponentRow& row) {
  try {
    (void)store.read(row);
    return std::nullopt;
  } catch (const FormatError& e) {
    return std::string(e.what());
  } catch (const IoError& e) { // a missing or unreadable shard
    return std::string(e.what());
  }
}

CheckReport check_store(const ComponentStore& store, Progress& progress, const CancelToken& cancel) {
  const auto start = std::chrono::steady_clock::now();
  CheckReport report;
  report.index_has_row_checksums = store.has_row_checksums();
  auto rows = store.query();
  progress.begin("checking", rows.size(), "components");
  for (const auto& row : rows) {
    cancel.throw_if_cancelled();
    if (!row.row_checksum) ++report.rows_without_checksum;
    if (auto problem = verify_component(store, row)) report.damaged.push_back({row.key, row.location, *problem});
    progress.update(++report.checked);
  }
  progress.end();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

} // namespace geotandem::store
