// ProgressReporter: the one progress display of the command-line tool. For each stage it shows
// done/total, the rate and an ETA: redrawn in place on a terminal, as a line every few seconds
// when stderr is not a terminal (cron logs), as JSON lines with --progress=json (one object per
// update: {"stage", "done", "total", "unit", "rate", "eta_s", "elapsed_s"}), and not at all with
// --quiet. Updates are throttled, so calling Update often is cheap.
// Thread-safety: Update may be called from several threads; it takes a mutex only when it draws.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "common/duration_text.h"  // FormatDuration, for the summaries

namespace motif {

enum class ProgressMode { kAuto, kQuiet, kJson };

class ProgressReporter {
 public:
  explicit ProgressReporter(ProgressMode mode);

  // Starts a stage: "import", "synth", "verify", ... `unit` names what is counted ("frames").
  void BeginStage(const std::string& stage, uint64_t total, const std::string& unit);
  // Sets how much of the current stage is done.
  void Update(uint64_t done);
  // Ends the stage and prints its final line (with the elapsed time).
  void EndStage();
  // A message line that does not disturb the progress display (suppressed by --quiet).
  void Note(const std::string& message);

  // For engine callbacks that report (stage, done, total): begins a stage whenever the name
  // changes (ending the one before) and updates it. EndStages() ends the last one.
  void StageUpdate(const std::string& stage, uint64_t done, uint64_t total,
                   const std::string& unit);
  void EndStages();

  ProgressMode mode() const { return mode_; }

 private:
  std::string open_stage_;  // StageUpdate's current stage
  void Draw(uint64_t done, bool final_line);

  ProgressMode mode_;
  bool is_terminal_;
  std::mutex mutex_;
  std::string stage_;
  std::string unit_;
  uint64_t total_ = 0;
  std::chrono::steady_clock::time_point stage_start_;
  std::atomic<int64_t> next_draw_ns_{0};
  bool drawn_in_place_ = false;
};

// Parses "auto" | "json" | "quiet" (also used for --quiet). Returns false on other text.
bool ParseProgressMode(const std::string& text, ProgressMode* mode);

// Units a second after `elapsed_seconds`, or 0 (not shown) before a quarter of a second: a stage
// that starts with its work done (reused) or ends within the clock's noise has no human rate.
double ProgressRate(uint64_t done, double elapsed_seconds);
// The line drawn for a stage: "[trellis] 1.20M/2.40M columns (50%)  40.0k columns/s  ETA 30.0s"
// while it runs, "[trellis] 2.40M columns in 1m00s (40.0k columns/s)" at its end; no rate while
// ProgressRate gives none.
std::string ProgressLine(const std::string& stage, const std::string& unit, uint64_t done,
                         uint64_t total, double elapsed_seconds, bool final_line);


}  // namespace motif
