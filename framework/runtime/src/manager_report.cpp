// The manager's report as JSON, for the store's run statistics (manager.hpp).
#include <nlohmann/json.hpp>

#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime {

namespace {
nlohmann::json counters_object(const tandem::SimplifyCounters& counters) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t i = 0; i < tandem::SimplifyCounters::all.size(); ++i)
    j[tandem::SimplifyCounters::names[i]] = counters.*tandem::SimplifyCounters::all[i];
  return j;
}
} // namespace

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
      {"manager",
       {{"cpu_seconds", manager_cpu_seconds},
        {"peak_rss_kb", manager_peak_rss_kb},
        {"messages_in", messages_in},
        {"messages_out", messages_out},
        {"commit_seconds", commit_seconds}}},
      {"worker_peak_rss_kb", worker_peak_rss_kb},
      {"input_triangles", counters.input_triangles},
      {"collapses", counters.collapses},
      {"peak_held_triangles", peak_held_triangles},
      {"counters", counters_object(counters)}};
  return j.dump();
}

std::string counters_to_json(const tandem::SimplifyCounters& counters) {
  return counters_object(counters).dump();
}

tandem::SimplifyCounters counters_from_json(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) throw ProtocolError("the collapse counters are not a JSON object: " + text.substr(0, 80));
  tandem::SimplifyCounters counters;
  for (std::size_t i = 0; i < tandem::SimplifyCounters::all.size(); ++i) {
    const auto it = j.find(tandem::SimplifyCounters::names[i]);
    if (it == j.end()) continue;
    if (!it->is_number_unsigned())
      throw ProtocolError(std::string("the collapse counter ") + tandem::SimplifyCounters::names[i] +
                          " is not a count: " + it->dump());
    counters.*tandem::SimplifyCounters::all[i] = it->get<std::uint64_t>();
  }
  return counters;
}

} // namespace geotandem::runtime
