// What one command shows while it works, and the times it keeps for its run record. On a
// terminal a bar is redrawn on stderr (stage, fraction, elapsed, time left); elsewhere each stage
// ends with one plain log line; with --quiet nothing is printed. The stage times are kept in
// every mode.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/progress.h"

namespace hm::cli {

class RunLog : public Progress {
 public:
  enum class Mode { kSilent, kLines, kBar };
  // kBar when stderr is a terminal, kLines otherwise, kSilent when quiet.
  static Mode mode_for(bool quiet);

  explicit RunLog(Mode mode, std::string prefix = "hullmesh", std::FILE* out = stderr);
  ~RunLog() override;

  // Ends the current stage (its time is kept) and starts `name`. A stage named again adds up.
  void stage(std::string_view name) override;
  // The current stage's fraction done, in [0, 1]; redraws the bar at most 10 times a second.
  void update(double fraction) override;
  // Ends the current stage; further stage() calls start new ones.
  void finish();
  // A stage timed by someone else (a library report's own seconds), kept after the current one.
  void add(std::string_view name, double seconds);

  // Seconds per stage in first-seen order. Call after finish() for complete figures.
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
  Mode mode() const { return mode_; }

 private:
  using Clock = std::chrono::steady_clock;
  void end_stage();
  void draw(double fraction);
  void clear_bar();

  Mode mode_;
  std::string prefix_;
  std::FILE* out_;
  std::vector<std::pair<std::string, double>> stages_;
  std::string current_;
  Clock::time_point started_{}, last_draw_{};
  bool bar_drawn_ = false;
};

}  // namespace hm::cli
