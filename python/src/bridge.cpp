#include "bridge.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <iostream>
#include <optional>
#include <thread>
#include <vector>

#include "geotandem/core/error.hpp"

namespace py = pybind11;

namespace geotandem::python {

ReportMode parse_report_mode(const std::string& text) {
  if (text == "terminal") return ReportMode::terminal;
  if (text == "callback") return ReportMode::callback;
  if (text == "quiet") return ReportMode::quiet;
  throw InvalidArgument("unknown progress mode '" + text + "'", {}, "use terminal, callback or quiet");
}

// What the work's threads leave for the main thread: log text and the state of the tasks.
struct Reporting::Shared {
  struct Task {
    std::string label, unit;
    std::uint64_t done = 0, total = 0;
    std::chrono::steady_clock::time_point start;
    std::string state = "running";
    bool changed = true;
    std::uint64_t id = 0; // stable while flush() drops finished tasks from the vector
  };
  std::mutex mutex;
  std::string log;
  std::vector<Task> tasks; // in order of begin(); shown and dropped by flush()
  std::uint64_t next_id = 1;
};

// A Progress that records its task for flush().
class Reporting::Recording final : public Progress {
public:
  explicit Recording(std::shared_ptr<Shared> shared) : shared_(std::move(shared)) {}
  void begin(const std::string& label, std::uint64_t total, const std::string& unit) override {
    std::lock_guard lock(shared_->mutex);
    done_ = 0;
    Shared::Task task;
    task.label = label, task.unit = unit, task.total = total, task.start = std::chrono::steady_clock::now();
    task.id = id_ = shared_->next_id++;
    shared_->tasks.push_back(task);
  }
  void update(std::uint64_t done) override {
    std::lock_guard lock(shared_->mutex);
    if (done <= done_ && done_ != 0) return;
    done_ = done;
    if (auto* t = task()) t->done = done, t->changed = true;
  }
  void end() override { finish("done"); }
  void stop() override { finish("stopped"); }

private:
  void finish(const char* state) {
    std::lock_guard lock(shared_->mutex);
    if (auto* t = task()) t->state = state, t->changed = true;
  }
  // This recording's task, found by its id: flush() compacts the vector, so an index would point
  // at another task once an earlier one has ended (a run has few tasks running at once).
  Shared::Task* task() {
    for (auto& t : shared_->tasks)
      if (t.id == id_) return &t;
    return nullptr;
  }
  std::shared_ptr<Shared> shared_;
  std::uint64_t id_ = 0;
};

// A stream buffer that appends the logger's lines to Shared::log.
class Reporting::Buffer final : public std::streambuf {
public:
  explicit Buffer(std::shared_ptr<Shared> shared) : shared_(std::move(shared)) {}

protected:
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    std::lock_guard lock(shared_->mutex);
    shared_->log.append(s, static_cast<std::size_t>(n));
    return n;
  }
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) {
      std::lock_guard lock(shared_->mutex);
      shared_->log.push_back(static_cast<char>(c));
    }
    return c;
  }

private:
  std::shared_ptr<Shared> shared_;
};

Reporting::Reporting(ReportMode mode, py::object sink)
    : mode_(mode), sink_(std::move(sink)), shared_(std::make_shared<Shared>()) {
  if (mode_ == ReportMode::terminal) {
    log_ = std::make_unique<Logger>(std::cerr);
  } else {
    buffer_ = std::make_unique<Buffer>(shared_);
    stream_ = std::make_unique<std::ostream>(buffer_.get());
    log_ = std::make_unique<Logger>(*stream_, mode_ == ReportMode::quiet ? LogLevel::warning : LogLevel::info);
  }
}

Reporting::~Reporting() = default;

std::unique_ptr<Progress> Reporting::progress() {
  switch (mode_) {
  case ReportMode::terminal: return make_stderr_progress(false);
  case ReportMode::callback: return std::make_unique<Recording>(shared_);
  case ReportMode::quiet: break;
  }
  return std::make_unique<NullProgress>();
}

void Reporting::flush() {
  std::string log;
  std::vector<Shared::Task> tasks;
  {
    std::lock_guard lock(shared_->mutex);
    log.swap(shared_->log);
    for (auto& t : shared_->tasks)
      if (t.changed) tasks.push_back(t), t.changed = false;
    // Finished tasks are shown one last time, then forgotten (a run has many).
    std::size_t kept = 0;
    for (auto& t : shared_->tasks)
      if (t.state == "running") shared_->tasks[kept++] = t;
    shared_->tasks.resize(kept);
  }
  if (sink_.is_none()) return;
  if (!log.empty()) sink_("log", log);
  const auto now = std::chrono::steady_clock::now();
  for (const auto& t : tasks)
    sink_("progress", t.label, t.done, t.total, t.unit, std::chrono::duration<double>(now - t.start).count(), t.state);
}

void run_cancellable(const std::function<void()>& work, const CancelToken& cancel, Reporting& reporting) {
  std::mutex mutex;
  std::condition_variable ended;
  bool finished = false;
  std::exception_ptr failure;
  std::optional<py::error_already_set> interruption;
  {
    py::gil_scoped_release release;
    std::thread thread([&] {
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard lock(mutex);
      finished = true;
      ended.notify_all();
    });
    for (;;) {
      {
        std::unique_lock lock(mutex);
        if (ended.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished; })) break;
      }
      py::gil_scoped_acquire acquire;
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        reporting.flush();
      } catch (py::error_already_set& e) {
        // The first exception (KeyboardInterrupt, from the signal handler or raised inside the
        // sink) is kept; later ones while the work winds down are dropped.
        if (!interruption) interruption.emplace(e); // a copy: `e` is this catch's own
        cancel.cancel();
      }
    }
    thread.join();
  }
  try {
    reporting.flush();
  } catch (py::error_already_set& e) {
    if (!interruption) interruption.emplace(std::move(e));
  }
  if (interruption) {
    interruption->restore();
    interruption.reset();
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
}

} // namespace geotandem::python
