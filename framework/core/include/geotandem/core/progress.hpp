#pragma once
// Progress reporting for long work. A task calls begin(), then advance()/update() as it goes, then
// end(), or stop() when an error or an interruption ends it early. The CLI picks the reporter: a
// bar that redraws itself on a terminal, plain lines (every 10 % or every 10 s) in CI and log files,
// or nothing. Both say how long the rest should take once the rate so far can tell.

#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace geotandem {

// The time the rest of a task should take at the rate so far: `elapsed` seconds for `done` of
// `total` units. None while that says little: before 5 s and 2 % of the units, or when done.
std::optional<double> seconds_left(double elapsed, std::uint64_t done, std::uint64_t total);
// A duration for people: "40 s", "12 min", "1 h 05 min".
std::string duration_text(double seconds);

class Progress {
public:
  virtual ~Progress() = default;
  // Starts a task of `total` units (0: unknown total). `unit` names what is counted ("layers").
  virtual void begin(const std::string& label, std::uint64_t total, const std::string& unit) = 0;
  // Sets the number of units done so far (monotonic; smaller values are ignored).
  virtual void update(std::uint64_t done) = 0;
  // Ends the task; prints the elapsed time.
  virtual void end() = 0;
  // Ends the task before it finished (an error, an interruption): says where it stopped.
  virtual void stop() {}
  void advance(std::uint64_t n = 1);

protected:
  std::uint64_t done_ = 0;
};

// Discards everything.
class NullProgress final : public Progress {
public:
  void begin(const std::string&, std::uint64_t, const std::string&) override { done_ = 0; }
  void update(std::uint64_t done) override { done_ = done; }
  void end() override {}
};

// Writes to a stream: a redrawn bar when `interactive`, else plain lines at most every
// `min_interval` and at each 10 % step.
class StreamProgress final : public Progress {
public:
  StreamProgress(std::ostream& out, bool interactive,
                 std::chrono::milliseconds min_interval = std::chrono::seconds(10));
  void begin(const std::string& label, std::uint64_t total, const std::string& unit) override;
  void update(std::uint64_t done) override;
  void end() override;
  void stop() override;

private:
  enum class Line { running, done, stopped };
  void draw(Line kind);

  std::ostream* out_;
  bool interactive_;
  std::chrono::milliseconds min_interval_;
  std::string label_;
  std::string unit_;
  std::uint64_t total_ = 0;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex mutex_;
};

// The reporter a command-line program should use on stderr: a bar when stderr is a terminal and
// the CI variable is unset, plain lines otherwise; nothing when `quiet`.
std::unique_ptr<Progress> make_stderr_progress(bool quiet);

} // namespace geotandem
