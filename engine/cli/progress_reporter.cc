#include "engine/cli/progress_reporter.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace motif {
namespace {

std::string FormatSeconds(double seconds) {
  char buffer[32];
  if (seconds < 0 || !std::isfinite(seconds)) return "?";
  if (seconds < 60) {
    std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
  } else if (seconds < 3600) {
    std::snprintf(buffer, sizeof buffer, "%dm%02ds", static_cast<int>(seconds) / 60,
                  static_cast<int>(seconds) % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%dh%02dm", static_cast<int>(seconds) / 3600,
                  (static_cast<int>(seconds) / 60) % 60);
  }
  return buffer;
}

std::string FormatCount(double value) {
  char buffer[32];
  if (value >= 1e9) {
    std::snprintf(buffer, sizeof buffer, "%.2fG", value / 1e9);
  } else if (value >= 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.2fM", value / 1e6);
  } else if (value >= 1e4) {
    std::snprintf(buffer, sizeof buffer, "%.1fk", value / 1e3);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
  }
  return buffer;
}

}  // namespace

bool ParseProgressMode(const std::string& text, ProgressMode* mode) {
  if (text == "auto") {
    *mode = ProgressMode::kAuto;
  } else if (text == "json") {
    *mode = ProgressMode::kJson;
  } else if (text == "quiet" || text == "none") {
    *mode = ProgressMode::kQuiet;
  } else {
    return false;
  }
  return true;
}

ProgressReporter::ProgressReporter(ProgressMode mode)
    : mode_(mode), is_terminal_(::isatty(STDERR_FILENO) == 1) {}

void ProgressReporter::BeginStage(const std::string& stage, uint64_t total,
                                  const std::string& unit) {
  std::lock_guard<std::mutex> lock(mutex_);
  stage_ = stage;
  unit_ = unit;
  total_ = total;
  stage_start_ = std::chrono::steady_clock::now();
  next_draw_ns_.store(0);
  drawn_in_place_ = false;
}

void ProgressReporter::Update(uint64_t done) {
  if (mode_ == ProgressMode::kQuiet) return;
  const int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::steady_clock::now().time_since_epoch())
                             .count();
  int64_t next = next_draw_ns_.load(std::memory_order_relaxed);
  if (now_ns < next) return;
  // Terminals redraw 5 times a second; logs get a line every 5 s; JSON every second.
  const int64_t interval_ns =
      mode_ == ProgressMode::kJson ? 1'000'000'000 : (is_terminal_ ? 200'000'000 : 5'000'000'000);
  if (!next_draw_ns_.compare_exchange_strong(next, now_ns + interval_ns)) return;
  std::lock_guard<std::mutex> lock(mutex_);
  Draw(done, false);
}

void ProgressReporter::EndStage() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ != ProgressMode::kQuiet) Draw(total_, true);
}

void ProgressReporter::Note(const std::string& message) {
  if (mode_ == ProgressMode::kQuiet) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (mode_ == ProgressMode::kJson) {
    nlohmann::json line = {{"stage", stage_}, {"note", message}};
    std::fprintf(stderr, "%s\n", line.dump().c_str());
    return;
  }
  if (drawn_in_place_) std::fprintf(stderr, "\r\033[K");
  std::fprintf(stderr, "%s\n", message.c_str());
  drawn_in_place_ = false;
}

double ProgressRate(uint64_t done, double elapsed_seconds) {
  // No rate from the first moments of a stage: a stage reported first with work already done
  // (reused, or faster than the clock) would show billions a second.
  constexpr double kLeastElapsedForRate = 0.25;
  return elapsed_seconds >= kLeastElapsedForRate ? static_cast<double>(done) / elapsed_seconds
                                                 : 0.0;
}

std::string ProgressLine(const std::string& stage, const std::string& unit, uint64_t done,
                         uint64_t total, double elapsed_seconds, bool final_line) {
  const double rate = ProgressRate(done, elapsed_seconds);
  const std::string rate_text = rate > 0 ? FormatCount(rate) + " " + unit + "/s" : "";
  char line[256];
  if (final_line) {
    std::snprintf(line, sizeof line, "[%s] %s %s in %s%s%s%s", stage.c_str(),
                  FormatCount(static_cast<double>(done)).c_str(), unit.c_str(),
                  FormatSeconds(elapsed_seconds).c_str(), rate > 0 ? " (" : "", rate_text.c_str(),
                  rate > 0 ? ")" : "");
  } else {
    const double percent = total > 0 ? 100.0 * static_cast<double>(done) / total : 0.0;
    const double eta = rate > 0 && total >= done ? static_cast<double>(total - done) / rate : -1.0;
    // All done (the stage is finishing): nothing left to estimate.
    const std::string eta_text =
        total > 0 && done >= total ? "" : "  ETA " + FormatSeconds(eta);
    std::snprintf(line, sizeof line, "[%s] %s/%s %s (%.0f%%)%s%s%s", stage.c_str(),
                  FormatCount(static_cast<double>(done)).c_str(),
                  FormatCount(static_cast<double>(total)).c_str(), unit.c_str(), percent,
                  rate > 0 ? "  " : "", rate_text.c_str(), eta_text.c_str());
  }
  return line;
}

void ProgressReporter::Draw(uint64_t done, bool final_line) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start_).count();
  const double rate = ProgressRate(done, elapsed);
  const double eta = rate > 0 && total_ >= done ? static_cast<double>(total_ - done) / rate : -1.0;
  if (mode_ == ProgressMode::kJson) {
    nlohmann::json line = {{"stage", stage_},      {"done", done},          {"total", total_},
                           {"unit", unit_},        {"rate", rate},          {"eta_s", eta},
                           {"elapsed_s", elapsed}, {"finished", final_line}};
    std::fprintf(stderr, "%s\n", line.dump().c_str());
    return;
  }
  const std::string text = ProgressLine(stage_, unit_, done, total_, elapsed, final_line);
  const char* line = text.c_str();
  if (is_terminal_) {
    std::fprintf(stderr, "\r\033[K%s%s", line, final_line ? "\n" : "");
    drawn_in_place_ = !final_line;
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
  std::fflush(stderr);
}

void ProgressReporter::StageUpdate(const std::string& stage, uint64_t done, uint64_t total,
                                   const std::string& unit) {
  if (stage != open_stage_) {
    if (!open_stage_.empty()) EndStage();
    open_stage_ = stage;
    BeginStage(stage, total, unit);
  }
  Update(done);
}

void ProgressReporter::EndStages() {
  if (open_stage_.empty()) return;
  EndStage();
  open_stage_.clear();
}

}  // namespace motif
