#include "cli/run_log.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace hm::cli {
namespace {

constexpr int kBarWidth = 24;
constexpr double kRedrawSeconds = 0.1;

}  // namespace

RunLog::Mode RunLog::mode_for(bool quiet) {
  if (quiet) return Mode::kSilent;
  return ::isatty(STDERR_FILENO) ? Mode::kBar : Mode::kLines;
}

RunLog::RunLog(Mode mode, std::string prefix, std::FILE* out)
    : mode_(mode), prefix_(std::move(prefix)), out_(out) {}

RunLog::~RunLog() { clear_bar(); }

void RunLog::stage(std::string_view name) {
  // A library stage announcing itself inside the caller's stage of the same name continues it.
  if (name == current_) return;
  end_stage();
  current_ = std::string(name);
  started_ = Clock::now();
  if (mode_ == Mode::kBar) draw(0);
}

void RunLog::update(double fraction) {
  if (mode_ != Mode::kBar || current_.empty()) return;
  const Clock::time_point now = Clock::now();
  if (std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds) return;
  draw(std::clamp(fraction, 0.0, 1.0));
}

void RunLog::finish() {
  end_stage();
  clear_bar();
}

void RunLog::add(std::string_view name, double seconds) {
  auto it =
      std::find_if(stages_.begin(), stages_.end(), [&](const auto& s) { return s.first == name; });
  if (it == stages_.end()) {
    stages_.emplace_back(std::string(name), seconds);
  } else {
    it->second += seconds;
  }
}

void RunLog::end_stage() {
  if (current_.empty()) return;
  const double seconds = std::chrono::duration<double>(Clock::now() - started_).count();
  add(current_, seconds);
  if (mode_ == Mode::kLines) {
    std::fprintf(out_, "%s: %s done in %.3f s\n", prefix_.c_str(), current_.c_str(), seconds);
    std::fflush(out_);
  }
  current_.clear();
}

void RunLog::draw(double fraction) {
  last_draw_ = Clock::now();
  const double elapsed = std::chrono::duration<double>(last_draw_ - started_).count();
  const int filled = static_cast<int>(std::lround(fraction * kBarWidth));
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kBarWidth - filled), '.');
  char left[32] = "";
  // Time left from the stage's own rate so far; nothing until there is a rate to go on.
  if (fraction > 0.02 && fraction < 1) {
    std::snprintf(left, sizeof left, ", ~%.1f s left", elapsed * (1 - fraction) / fraction);
  }
  std::fprintf(out_, "\r\033[K%s: %-12s [%s] %3.0f%% %.1f s%s", prefix_.c_str(), current_.c_str(),
               bar.c_str(), 100 * fraction, elapsed, left);
  std::fflush(out_);
  bar_drawn_ = true;
}

void RunLog::clear_bar() {
  if (!bar_drawn_) return;
  std::fprintf(out_, "\r\033[K");
  std::fflush(out_);
  bar_drawn_ = false;
}

}  // namespace hm::cli
