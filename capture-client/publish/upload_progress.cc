#include "capture-client/publish/upload_progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

namespace reenact::capture {

namespace {

std::string Printf(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

// "2.3/4.6 MB": both in the unit of the total.
std::string BytesOfTotal(uint64_t done, uint64_t total) {
  const std::string total_text = FormatBytes(total);
  const std::string unit = total_text.substr(total_text.find(' '));
  std::string done_text = FormatBytes(done);
  if (unit == " B") return std::to_string(done) + "/" + total_text;
  static constexpr struct {
    const char* unit;
    double scale;
  } kUnits[] = {{" kB", 1e3}, {" MB", 1e6}, {" GB", 1e9}, {" TB", 1e12}};
  for (const auto& u : kUnits) {
    if (unit == u.unit) {
      const double d = static_cast<double>(done) / u.scale;
      return Printf(d < 10 ? "%.2f" : d < 100 ? "%.1f" : "%.0f", d) + "/" + total_text;
    }
  }
  return done_text + "/" + total_text;
}

std::string RateAndEta(const UploadSnapshot& s, const char* separator) {
  const double rate = s.RateBytesPerS();
  const auto eta = s.EtaS();
  std::string text = rate > 0 ? FormatBytes(static_cast<uint64_t>(std::llround(rate))) + "/s"
                              : std::string("-- B/s");
  text += separator;
  text += "ETA " + (s.done_bytes >= s.total_bytes ? std::string("0 s")
                    : eta                         ? FormatDuration(*eta)
                                                  : std::string("--"));
  return text;
}

double NowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int UploadSnapshot::Percent() const {
  if (total_bytes == 0) return 100;
  const uint64_t done = std::min(done_bytes, total_bytes);
  return static_cast<int>((done * 100) / total_bytes);
}

double UploadSnapshot::RateBytesPerS() const {
  if (sent_bytes == 0 || elapsed_s <= 0) return 0;
  return static_cast<double>(sent_bytes) / elapsed_s;
}

std::optional<double> UploadSnapshot::EtaS() const {
  const double rate = RateBytesPerS();
  if (rate <= 0) return std::nullopt;
  const uint64_t left = total_bytes > done_bytes ? total_bytes - done_bytes : 0;
  return static_cast<double>(left) / rate;
}

std::string FormatBytes(uint64_t bytes) {
  if (bytes < 1000) return std::to_string(bytes) + " B";
  static constexpr struct {
    const char* unit;
    double scale;
  } kUnits[] = {{"kB", 1e3}, {"MB", 1e6}, {"GB", 1e9}, {"TB", 1e12}};
  const double value = static_cast<double>(bytes);
  for (size_t i = 0; i < std::size(kUnits); ++i) {
    const double scaled = value / kUnits[i].scale;
    // Rounded to 3 significant digits; move up a unit when that reaches 1000.
    const bool last = i + 1 == std::size(kUnits);
    if (scaled >= 999.5 && !last) continue;
    return Printf(scaled < 9.995   ? "%.2f"
                  : scaled < 99.95 ? "%.1f"
                                   : "%.0f",
                  scaled) +
           " " + kUnits[i].unit;
  }
  return std::to_string(bytes) + " B";
}

std::string FormatDuration(double seconds) {
  if (!(seconds > 0)) return "0 s";
  const double capped = std::min(seconds, 360000.0 * 24);  // a clear "very long", not overflow
  const long long s = static_cast<long long>(std::ceil(capped));
  char text[64];
  if (s < 60) {
    std::snprintf(text, sizeof(text), "%lld s", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof(text), "%lld min %02lld s", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof(text), "%lld h %02lld min", s / 3600, (s % 3600) / 60);
  }
  return text;
}

std::string FormatProgressLine(const UploadSnapshot& s) {
  char head[96];
  std::snprintf(head, sizeof(head), "progress %3d%% (%d/%d parts, ", s.Percent(), s.done_parts,
                s.total_parts);
  return head + BytesOfTotal(s.done_bytes, s.total_bytes) + ") " + RateAndEta(s, " ");
}

std::string FormatProgressBar(const UploadSnapshot& s, int bar_width) {
  bar_width = std::max(1, bar_width);
  const int percent = s.Percent();
  const int filled = percent * bar_width / 100;
  std::string bar(static_cast<size_t>(bar_width) + 2, '-');
  bar.front() = '[';
  bar.back() = ']';
  std::fill_n(bar.begin() + 1, filled, '#');
  char pct[16];
  std::snprintf(pct, sizeof(pct), " %3d%%  ", percent);
  return bar + pct + BytesOfTotal(s.done_bytes, s.total_bytes) + "  " + RateAndEta(s, "  ");
}

bool ProgressLineSchedule::Due(int percent, double now_s) {
  const bool first = last_percent_ < 0;
  const bool new_tenth = percent / 10 > last_percent_ / 10;
  const bool interval = percent > last_percent_ && now_s - last_time_s_ >= interval_s_;
  if (!first && !new_tenth && !interval) return false;
  last_percent_ = percent;
  last_time_s_ = now_s;
  return true;
}

void ProgressPrinter::Update(const UploadSnapshot& snapshot) {
  if (style_ == ProgressStyle::kNone) return;
  const double now = NowS();
  if (style_ == ProgressStyle::kLines) {
    if (schedule_.Due(snapshot.Percent(), now)) {
      std::fprintf(out_, "%s\n", FormatProgressLine(snapshot).c_str());
      std::fflush(out_);
    }
    return;
  }
  if (last_bar_s_ >= 0 && now - last_bar_s_ < 0.1) return;
  last_bar_s_ = now;
  std::fprintf(out_, "\r%s\033[K", FormatProgressBar(snapshot).c_str());
  std::fflush(out_);
  bar_open_ = true;
}

void ProgressPrinter::Finish(const UploadSnapshot& snapshot) {
  if (style_ == ProgressStyle::kNone) return;
  if (style_ == ProgressStyle::kLines) {
    if (schedule_.Due(snapshot.Percent(), NowS())) {
      std::fprintf(out_, "%s\n", FormatProgressLine(snapshot).c_str());
    }
  } else {
    std::fprintf(out_, "\r%s\033[K\n", FormatProgressBar(snapshot).c_str());
    bar_open_ = false;
  }
  std::fflush(out_);
}

void ProgressPrinter::Note(const std::string& line) {
  if (bar_open_) std::fprintf(out_, "\r\033[K");
  std::fprintf(out_, "%s\n", line.c_str());
  std::fflush(out_);
  bar_open_ = false;
  last_bar_s_ = -1;
}

ProgressStyle DefaultProgressStyle() {
  return isatty(STDOUT_FILENO) ? ProgressStyle::kBar : ProgressStyle::kLines;
}

}  // namespace reenact::capture
