#include "io/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace grainlab {

Progress::Progress(std::string label, bool quiet, double interval_s)
    : label_(std::move(label)),
      quiet_(quiet),
      tty_(isatty(fileno(stderr)) != 0),
      interval_s_(tty_ ? 0.25 : interval_s),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void Progress::update(double fraction, const std::string& detail) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool known = fraction >= 0.0;
  if (known && first_fraction_ < 0.0) first_fraction_ = fraction, first_update_ = now;
  if (std::chrono::duration<double>(now - last_).count() < interval_s_) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::string text;
  if (known) {
    // From this session's rate since the first update: a resumed run did the part before
    // first_fraction_ earlier.
    const double done = fraction - first_fraction_;
    const double since_first = std::chrono::duration<double>(now - first_update_).count();
    const double eta = done > 0.0 ? since_first * (1.0 - fraction) / done : 0.0;
    text = fmt::format("{}: {:5.1f} %  {}  elapsed {:.0f} s  ETA {:.0f} s", label_,
                       100.0 * fraction, detail, elapsed, eta);
  } else {
    text = fmt::format("{}: {}  elapsed {:.0f} s", label_, detail, elapsed);
  }
  if (tty_)
    fmt::print(stderr, "\r{:<100}", text);
  else
    fmt::print(stderr, "{}\n", text);
  std::fflush(stderr);
}

void Progress::message(const std::string& text) {
  if (quiet_) return;
  if (tty_)
    fmt::print(stderr, "\r{:<100}\n", text);
  else
    fmt::print(stderr, "{}\n", text);
  std::fflush(stderr);
}

void Progress::finish(const std::string& detail) {
  if (quiet_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string text = fmt::format("{}: done, {}  wall time {:.1f} s", label_, detail, elapsed);
  if (tty_)
    fmt::print(stderr, "\r{:<100}\n", text);
  else
    fmt::print(stderr, "{}\n", text);
}

}  // namespace grainlab
