#pragma once
// Progress of an upload for people: a redrawn bar with rate and ETA on a terminal, plain
// lines otherwise (logs, CI, pipes), printed when a tenth more is done or every few seconds.
//
//   terminal: [##########----------]  50%  2.3/4.6 MB  1.2 MB/s  ETA 2 s
//   lines:    progress  50% (61/121 parts, 2.3/4.6 MB) 1.2 MB/s ETA 2 s
//
// Fraction done counts the bytes the server already held (a resumed upload starts above 0);
// the rate counts only bytes sent in this run, over the time since sending began, and
// ETA = bytes still to send / rate (unknown, "--", before the first byte was sent).

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

namespace reenact::capture {

struct UploadSnapshot {
  uint64_t total_bytes = 0;  // every part of the clip
  uint64_t done_bytes = 0;   // held by the server: before this run, or sent in it
  uint64_t sent_bytes = 0;   // sent in this run (<= done_bytes)
  int total_parts = 0;
  int done_parts = 0;
  double elapsed_s = 0;  // since sending began

  // floor(100 * done / total) in [0, 100]; 100 for an empty upload.
  int Percent() const;
  // Bytes per second of this run; 0 before anything was sent or time passed.
  double RateBytesPerS() const;
  // Seconds still needed at the current rate; nullopt while the rate is unknown.
  std::optional<double> EtaS() const;
};

// "0 B", "512 B", "48.2 kB", "4.6 MB", "1.20 GB" (SI units, as transfer rates are quoted).
std::string FormatBytes(uint64_t bytes);
// "0 s", "42 s", "3 min 05 s", "2 h 07 min" (rounded up to whole seconds).
std::string FormatDuration(double seconds);
// "progress  50% (61/121 parts, 2.3/4.6 MB) 1.2 MB/s ETA 2 s"
std::string FormatProgressLine(const UploadSnapshot& snapshot);
// "[##########----------]  50%  2.3/4.6 MB  1.2 MB/s  ETA 2 s", bar_width cells of '#'/'-'.
std::string FormatProgressBar(const UploadSnapshot& snapshot, int bar_width = 30);

// When the line mode prints: on the first update, whenever the percentage enters a new tenth
// (10%, 20%, ... 100%), and when interval_s passed since the last line with some progress.
class ProgressLineSchedule {
 public:
  explicit ProgressLineSchedule(double interval_s = 5.0) : interval_s_(interval_s) {}
  // True if a line should be printed for this percentage at this time (then it is recorded).
  bool Due(int percent, double now_s);

 private:
  double interval_s_;
  int last_percent_ = -1;
  double last_time_s_ = 0;
};

enum class ProgressStyle { kBar, kLines, kNone };

// Prints the progress of one upload to `out` in the given style (kBar redraws one line with
// '\r', at most every 0.1 s). Notes (retries) go on their own line.
class ProgressPrinter {
 public:
  ProgressPrinter(std::FILE* out, ProgressStyle style) : out_(out), style_(style) {}
  void Update(const UploadSnapshot& snapshot);
  // The last update, always shown; ends the bar's line.
  void Finish(const UploadSnapshot& snapshot);
  void Note(const std::string& line);

 private:
  std::FILE* out_;
  ProgressStyle style_;
  ProgressLineSchedule schedule_;
  double last_bar_s_ = -1;
  bool bar_open_ = false;
};

// kBar when stdout is a terminal, else kLines.
ProgressStyle DefaultProgressStyle();

}  // namespace reenact::capture
