// Small pieces of the manager's loop (manager_support.hpp).
#include "manager_support.hpp"

#include <sys/resource.h>

#include <cstdlib>
#include <random>

namespace geotandem::runtime::detail {

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::int64_t peak_rss_kb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

std::string random_hex(std::size_t n) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::random_device rd;
  std::string s;
  for (std::size_t i = 0; i < n; ++i)
    s += kDigits[rd() % 16];
  return s;
}

Message task_message(const Decision& d, const tandem::BlockTree& tree) {
  Message m;
  switch (d.kind) {
  case TaskKind::extract: {
    m.kind = MessageKind::extract;
    const volume::Box& b = tree.node(d.leaf).cells;
    m.box = {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]};
    m.number = static_cast<std::uint64_t>(d.leaf);
    break;
  }
  case TaskKind::send:
    m.kind = MessageKind::send;
    m.number = d.target;
    break;
  case TaskKind::merge: m.kind = MessageKind::merge; break;
  case TaskKind::wait:
    m.kind = MessageKind::wait;
    m.number = 20;
    break;
  case TaskKind::finished:
    m.kind = MessageKind::finished;
    m.number = d.final ? 1 : 0;
    break;
  }
  return m;
}

std::size_t extract_batch_cap() {
  const char* text = std::getenv("GEOTANDEM_EXTRACT_BATCH");
  if (text && *text) {
    char* end = nullptr;
    const long long n = std::strtoll(text, &end, 10);
    if (end && *end == '\0' && n > 0) return static_cast<std::size_t>(n);
  }
  return 4096;
}

} // namespace geotandem::runtime::detail
