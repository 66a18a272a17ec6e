// The worker's walltime (walltime.hpp).
#include "walltime.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>

namespace geotandem::runtime::detail {

namespace {

using Clock = std::chrono::steady_clock;
const Clock::time_point process_start = Clock::now(); // when the library was loaded: the worker's start

std::optional<double> seconds_in(const char* name) {
  const char* text = std::getenv(name);
  if (!text || !*text) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (!(v > 0) || (end && *end)) return std::nullopt;
  return v;
}

double margin_for(double walltime) {
  return seconds_in(walltime_margin_variable).value_or(walltime_margin(walltime));
}

double used_seconds() {
  return std::chrono::duration<double>(Clock::now() - process_start).count();
}

// Whole seconds, or tenths under 10 s (tests use walltimes of a few seconds).
std::string seconds_text(double s) {
  if (s >= 10) return std::to_string(static_cast<long long>(s));
  const long long tenths = std::llround(s * 10);
  return std::to_string(tenths / 10) + "." + std::to_string(tenths % 10);
}

} // namespace

double walltime_margin(double walltime) {
  return std::min(std::clamp(walltime * 0.05, 60.0, 600.0), walltime / 4);
}

bool walltime_nearly_over() {
  const std::optional<double> walltime = seconds_in(walltime_variable);
  return walltime && used_seconds() + margin_for(*walltime) / 2 >= *walltime;
}

std::string walltime_exhausted() {
  const std::optional<double> walltime = seconds_in(walltime_variable);
  if (!walltime) return {};
  const double margin = margin_for(*walltime);
  const double used = used_seconds();
  if (used + margin < *walltime) return {};
  return seconds_text(std::max(0.0, *walltime - used)) + " s left of its " + seconds_text(*walltime) +
         " s walltime (it stops " + seconds_text(margin) + " s before)";
}

} // namespace geotandem::runtime::detail
