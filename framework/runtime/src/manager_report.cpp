// The manager's report as JSON, for the store's run statistics (manager.hpp).
#include <nlohmann/json.hpp>

#include "geotandem/runtime/manager.hpp"

namespace geotandem::runtime {

std::string ManagerReport::to_json() const {
  const nlohmann::json j = {
      {"workers", workers},
      {"deaths", deaths},
      {"restarts", restarts},
      {"leaves", leaves},
      {"skipped_leaves", skipped_leaves},
      {"tasks", {{"extract", extract}, {"send", send}, {"merge", merge}, {"finish", finish}}},
      {"redone_leaves", redone_leaves},
      {"retirements", {{"workers", retirements}, {"handed_back_leaves", handed_back}}},
      {"seconds",
       {{"total", seconds}, {"extract", seconds_extract}, {"merge", seconds_merge}, {"finish", seconds_finish}}},
      {"bytes",
       {{"surfaces", surface_bytes}, {"largest_surface", largest_surface}, {"in", bytes_in}, {"out", bytes_out}}},
      {"relay",
       {{"peak_held_bytes", relay_peak_held}, {"spilled", relay_spilled}, {"spilled_bytes", relay_spilled_bytes}}},
      {"dropped_messages", dropped_messages},
      {"components", components},
      {"duplicates", duplicates},
      {"repaired", repaired},
      {"manager", {{"cpu_seconds", manager_cpu_seconds}, {"peak_rss_kb", manager_peak_rss_kb}}},
      {"worker_peak_rss_kb", worker_peak_rss_kb},
      {"input_triangles", input_triangles},
      {"collapses", collapses},
      {"peak_held_triangles", peak_held_triangles}};
  return j.dump();
}

} // namespace geotandem::runtime
