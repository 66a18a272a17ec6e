#include "geotandem/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace geotandem {

void Progress::advance(std::uint64_t n) {
  update(done_ + n);
}

std::optional<double> seconds_left(double elapsed, std::uint64_t done, std::uint64_t total) {
  if (total == 0 || done == 0 || done >= total || !(elapsed >= 5.0)) return std::nullopt;
  const double fraction = static_cast<double>(done) / static_cast<double>(total);
  if (fraction < 0.02) return std::nullopt;
  return elapsed * (1.0 - fraction) / fraction;
}

std::string duration_text(double seconds) {
  const auto s = static_cast<long long>(std::llround(std::max(0.0, seconds)));
  if (s < 60) return std::to_string(s) + " s";
  const long long minutes = (s + 30) / 60;
  if (minutes < 60) return std::to_string(minutes) + " min";
  std::ostringstream text;
  text << minutes / 60 << " h " << std::setw(2) << std::setfill('0') << minutes % 60 << " min";
  return text.str();
}

StreamProgress::StreamProgress(std::ostream& out, bool interactive, std::chrono::milliseconds min_interval)
    : out_(&out), interactive_(interactive), min_interval_(min_interval) {}

void StreamProgress::begin(const std::string& label, std::uint64_t total, const std::string& unit) {
  std::lock_guard lock(mutex_);
  label_ = label;
  unit_ = unit;
  total_ = total;
  done_ = 0;
  last_decile_ = 0; // the "started" line stands for 0 %
  start_ = last_draw_ = std::chrono::steady_clock::now();
  if (!interactive_) {
    *out_ << label_ << ": started";
    if (total_ > 0) *out_ << " (" << total_ << ' ' << unit_ << ')';
    *out_ << '\n' << std::flush;
  }
}

void StreamProgress::update(std::uint64_t done) {
  std::lock_guard lock(mutex_);
  if (done <= done_) return;
  done_ = done;
  auto now = std::chrono::steady_clock::now();
  if (interactive_) {
    if (now - last_draw_ >= std::chrono::milliseconds(100) || (total_ > 0 && done_ >= total_)) {
      last_draw_ = now;
      draw(Line::running);
    }
    return;
  }
  int decile = total_ > 0 ? static_cast<int>(10 * done_ / total_) : -1;
  // Fewer than ten units: no decile lines (each unit would be one); the time-based line remains.
  bool step = total_ >= 10 && decile > last_decile_ && decile < 10;
  if (step || now - last_draw_ >= min_interval_) {
    if (decile > last_decile_) last_decile_ = decile;
    last_draw_ = now;
    draw(Line::running);
  }
}

void StreamProgress::end() {
  std::lock_guard lock(mutex_);
  draw(Line::done);
}

void StreamProgress::stop() {
  std::lock_guard lock(mutex_);
  draw(Line::stopped);
}

void StreamProgress::draw(Line kind) {
  const bool final_line = kind != Line::running;
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::ostringstream line;
  line << label_ << ": ";
  if (total_ > 0) {
    double fraction = std::min(1.0, static_cast<double>(done_) / static_cast<double>(total_));
    if (interactive_) {
      constexpr int width = 30;
      int filled = static_cast<int>(fraction * width);
      line << '[' << std::string(filled, '#') << std::string(width - filled, '.') << "] ";
    }
    line << std::fixed << std::setprecision(0) << 100.0 * fraction << "% (" << done_ << '/' << total_ << ' ' << unit_
         << ')';
  } else {
    line << done_ << ' ' << unit_;
  }
  line << std::fixed << std::setprecision(1) << ", " << seconds << " s";
  if (kind == Line::done) line << ", done";
  if (kind == Line::stopped) line << ", stopped";
  if (kind == Line::running)
    if (const std::optional<double> left = seconds_left(seconds, done_, total_))
      line << ", about " << duration_text(*left) << " left";
  if (interactive_) {
    *out_ << '\r' << line.str() << "\x1b[K";
    if (final_line) *out_ << '\n';
  } else {
    *out_ << line.str() << '\n';
  }
  out_->flush();
}

std::unique_ptr<Progress> make_stderr_progress(bool quiet) {
  if (quiet) return std::make_unique<NullProgress>();
  bool interactive = ::isatty(STDERR_FILENO) == 1 && std::getenv("CI") == nullptr;
  return std::make_unique<StreamProgress>(std::cerr, interactive);
}

} // namespace geotandem
