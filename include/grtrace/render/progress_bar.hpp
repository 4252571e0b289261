// grtrace/render/progress_bar.hpp
// A thread-safe progress bar for long loops (renders), drawn on one terminal line:
//
//   render [############..................]  41.2%  1.23M rays/s  ETA 0:07
//
// - Shown only when the stream (stderr by default) is a terminal, so logs and pipes stay clean; ProgressMode
//   can force it on (tests) or off (--quiet).
// - advance() may be called from any number of threads: it is one atomic add plus, at most ~10 times a second,
//   one redraw by whichever thread crosses the redraw time (the others never block on it).
// - finish() draws the final state (elapsed time instead of ETA) and ends the line; it is idempotent, and
//   the destructor calls it, so an exception unwinding past the bar still leaves the terminal tidy.
// No dependency beyond the standard library and POSIX isatty().
#pragma once

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>
#include <utility>

namespace grtrace {

enum class ProgressMode {
  automatic,  ///< draw only if the stream is a terminal (isatty)
  always,     ///< draw even into a file or pipe (tests, forced progress)
  never,      ///< stay silent
};

class ProgressBar {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kRedrawInterval{100};
  static constexpr int kBarWidth = 30;

  /// `total` units of work (rays); `label` starts the line. The clock starts now; an enabled bar draws its
  /// 0% line immediately. `stream` must outlive the bar.
  explicit ProgressBar(long total, std::string label = "render", ProgressMode mode = ProgressMode::automatic,
                       std::FILE* stream = stderr)
      : total_(std::max(total, 0L)), label_(std::move(label)), stream_(stream), start_(Clock::now()) {
    switch (mode) {
      case ProgressMode::always:
        enabled_ = stream_ != nullptr;
        break;
      case ProgressMode::never:
        enabled_ = false;
        break;
      case ProgressMode::automatic:
        enabled_ = stream_ != nullptr && ::isatty(::fileno(stream_)) == 1;
        break;
    }
    if (enabled_) {
      std::lock_guard lock(mutex_);
      draw_locked(0, 0.0, false);
    }
  }

  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  ~ProgressBar() {
    try {
      finish();
    } catch (...) {  // never throw from a destructor
    }
  }

  /// True if this bar draws anything.
  bool enabled() const { return enabled_; }
  long total() const { return total_; }
  long done() const { return done_.load(std::memory_order_relaxed); }
  double elapsed_seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  /// Records `n` more units done. Thread-safe and cheap; redraws at most once per kRedrawInterval.
  void advance(long n = 1) {
    const long now_done = done_.fetch_add(n, std::memory_order_relaxed) + n;
    if (!enabled_) return;
    const auto t = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
    long long next = next_draw_ns_.load(std::memory_order_relaxed);
    if (t < next) return;
    const long long interval = std::chrono::duration_cast<std::chrono::nanoseconds>(kRedrawInterval).count();
    if (!next_draw_ns_.compare_exchange_strong(next, t + interval, std::memory_order_relaxed)) return;
    std::lock_guard lock(mutex_);
    if (finished_) return;
    draw_locked(std::max(now_done, done_.load(std::memory_order_relaxed)), static_cast<double>(t) * 1e-9, false);
  }

  /// Draws the final line (count so far, average rate, elapsed seconds) and a newline. Idempotent, thread-safe.
  void finish() {
    std::lock_guard lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (!enabled_) return;
    draw_locked(done_.load(std::memory_order_relaxed), elapsed_seconds(), true);
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }

  /// The text of one line (without the leading '\r' and trailing clear-to-end-of-line), for tests and for
  /// callers that want to log the final state themselves.
  static std::string format(const std::string& label, long done, long total, double seconds, bool final) {
    const double fraction =
        total > 0 ? std::clamp(static_cast<double>(done) / static_cast<double>(total), 0.0, 1.0) : 1.0;
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(static_cast<std::size_t>(kBarWidth), '.');
    std::fill_n(bar.begin(), filled, '#');
    const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
    char buffer[160];
    if (final) {
      std::snprintf(buffer, sizeof buffer, "%s [%s] %5.1f%%  %s rays/s  %.2f s", label.c_str(), bar.c_str(),
                    100.0 * fraction, format_rate(rate).c_str(), seconds);
    } else {
      std::string eta = "--:--";
      if (rate > 0.0 && done > 0) eta = format_duration(static_cast<double>(total - done) / rate);
      std::snprintf(buffer, sizeof buffer, "%s [%s] %5.1f%%  %s rays/s  ETA %s", label.c_str(), bar.c_str(),
                    100.0 * fraction, format_rate(rate).c_str(), eta.c_str());
    }
    return buffer;
  }

  /// 1234567 -> "1.23M", 12345 -> "12.3k", 12 -> "12".
  static std::string format_rate(double rate) {
    char buffer[32];
    if (!(rate >= 0.0) || rate > 1e15) return "?";
    if (rate >= 1e6) std::snprintf(buffer, sizeof buffer, "%.2fM", rate * 1e-6);
    else if (rate >= 1e3) std::snprintf(buffer, sizeof buffer, "%.1fk", rate * 1e-3);
    else std::snprintf(buffer, sizeof buffer, "%.0f", rate);
    return buffer;
  }

  /// 75 -> "1:15", 3725 -> "1:02:05" (rounded up to whole seconds).
  static std::string format_duration(double seconds) {
    if (!(seconds >= 0.0) || seconds > 1e8) return "--:--";
    const long s = static_cast<long>(seconds + 0.999);
    char buffer[32];
    if (s >= 3600) std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
    else std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
    return buffer;
  }

 private:
  void draw_locked(long done, double seconds, bool final) {
    // '\r' returns to the start of the line; ESC[K clears what a longer previous line left behind.
    std::fprintf(stream_, "\r%s\033[K", format(label_, done, total_, seconds, final).c_str());
    std::fflush(stream_);
  }

  long total_;
  std::string label_;
  std::FILE* stream_;
  Clock::time_point start_;
  bool enabled_ = false;
  bool finished_ = false;
  std::atomic<long> done_{0};
  std::atomic<long long> next_draw_ns_{std::chrono::duration_cast<std::chrono::nanoseconds>(kRedrawInterval).count()};
  std::mutex mutex_;
};

}  // namespace grtrace
