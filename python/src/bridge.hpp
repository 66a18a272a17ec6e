#pragma once
// Long C++ work called from Python: run in a thread of its own with the GIL released, while the
// calling (main) thread wakes every 100 ms to let Python handle signals and to show progress and
// log lines. KeyboardInterrupt cancels the work's token; the work stops at its next safe point,
// what it committed stays, and KeyboardInterrupt is raised once it has ended.

#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <mutex>
#include <ostream>
#include <sstream>
#include <string>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"

namespace geotandem::python {

// Where progress and log lines go. terminal: stderr, the command line's own lines (a bar on a
// terminal); callback: a Python callable `sink(kind, *payload)` called from the main thread
// ("log", text) and ("progress", label, done, total, unit, seconds, state) with state "running",
// "done" or "stopped" (a notebook draws one updating line); quiet: progress nowhere, warnings only.
enum class ReportMode { terminal, callback, quiet };
ReportMode parse_report_mode(const std::string& text);

// The reporters of one call: the logger and a progress factory for the chosen mode.
class Reporting {
public:
  Reporting(ReportMode mode, pybind11::object sink);
  ~Reporting();
  Logger& log() { return *log_; }
  std::unique_ptr<Progress> progress();
  // Hands what accumulated to the sink (GIL held; main thread). Throws error_already_set when the
  // sink raised.
  void flush();

private:
  struct Shared;
  class Recording;
  class Buffer;
  ReportMode mode_;
  pybind11::object sink_;
  std::shared_ptr<Shared> shared_;
  std::unique_ptr<std::streambuf> buffer_;
  std::unique_ptr<std::ostream> stream_;
  std::unique_ptr<Logger> log_;
};

// Runs `work` (which must not touch Python objects) in a thread with the GIL released, and returns
// when it has ended. Meanwhile, every 100 ms: PyErr_CheckSignals and reporting.flush(). A signal
// handler that raised (KeyboardInterrupt) cancels `cancel`; once the work has ended the exception
// is raised (error_already_set). The work's own exceptions are rethrown (the error translator
// makes them Python exceptions); its Cancelled after an interruption gives way to the
// KeyboardInterrupt. Call with the GIL held.
void run_cancellable(const std::function<void()>& work, const CancelToken& cancel, Reporting& reporting);

} // namespace geotandem::python
