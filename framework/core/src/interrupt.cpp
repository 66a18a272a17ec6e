#include "geotandem/core/interrupt.hpp"

#include <semaphore.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <ctime>
#include <thread>

namespace geotandem {
namespace {

std::atomic<bool>* g_flag = nullptr;
volatile std::sig_atomic_t g_signal = 0;
sem_t g_wakeup;
double g_grace = 0.8;

void write_text(const char* text) {
  std::size_t n = 0;
  while (text[n] != '\0')
    ++n;
  [[maybe_unused]] auto ignored = ::write(STDERR_FILENO, text, n);
}

extern "C" void on_signal(int signal) {
  if (g_signal != 0) { // the second signal: the user insists
    write_text("geotandem: interrupted again; stopping now\n");
    ::_exit(128 + signal);
  }
  g_signal = signal;
  if (g_flag) g_flag->store(true, std::memory_order_relaxed);
  ::sem_post(&g_wakeup); // async-signal-safe
}

void watchdog() {
  while (::sem_wait(&g_wakeup) != 0 && errno == EINTR) {
  }
  timespec pause{static_cast<time_t>(g_grace), static_cast<long>((g_grace - static_cast<time_t>(g_grace)) * 1e9)};
  while (::nanosleep(&pause, &pause) != 0 && errno == EINTR) {
  }
  const int signal = g_signal;
  write_text(signal == SIGTERM ? "geotandem: terminated; work done so far is kept\n"
                               : "geotandem: interrupted; work done so far is kept\n");
  ::_exit(128 + signal);
}

extern "C" void on_bus_error(int) {
  write_text("geotandem: error: a file being read was truncated or replaced by another process while it was "
             "mapped (SIGBUS) (copy the file again and rerun; work already stored is kept)\n");
  ::_exit(4);
}

} // namespace

void install_interrupt_handling(const CancelToken& cancel, double grace_seconds) {
  g_flag = cancel.raw_flag();
  g_grace = grace_seconds > 0 ? grace_seconds : 0.8;
  ::sem_init(&g_wakeup, 0, 0);
  std::thread(watchdog).detach();
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART; // reads and writes resume; the watchdog ends waits that never return
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  struct sigaction bus = {};
  bus.sa_handler = on_bus_error;
  sigemptyset(&bus.sa_mask);
  ::sigaction(SIGBUS, &bus, nullptr);
}

} // namespace geotandem
