#include "server/http/metrics.h"

#include <sstream>

namespace reenact::server {

void Metrics::Record(const std::string& route, int status, double seconds, uint64_t bytes_in,
                     uint64_t bytes_out) {
  std::lock_guard lock(mutex_);
  ++requests_[{route, status}];
  Histogram& h = latency_[route];
  for (size_t i = 0; i < kBucketsS.size(); ++i) {
    if (seconds <= kBucketsS[i]) {
      ++h.buckets[i];
      break;
    }
  }
  ++h.count;
  h.sum_s += seconds;
  bytes_in_ += bytes_in;
  bytes_out_ += bytes_out;
}

std::string Metrics::Render(int64_t draft_clips, int64_t published_clips) const {
  std::lock_guard lock(mutex_);
  std::ostringstream out;
  out << "# HELP reenact_http_requests_total HTTP requests by route and status.\n"
      << "# TYPE reenact_http_requests_total counter\n";
  for (const auto& [key, count] : requests_) {
    out << "reenact_http_requests_total{route=\"" << key.first << "\",status=\"" << key.second
        << "\"} " << count << "\n";
  }
  out << "# HELP reenact_http_request_duration_seconds Time to handle and answer a request.\n"
      << "# TYPE reenact_http_request_duration_seconds histogram\n";
  for (const auto& [route, h] : latency_) {
    uint64_t cumulative = 0;
    for (size_t i = 0; i < kBucketsS.size(); ++i) {
      cumulative += h.buckets[i];
      out << "reenact_http_request_duration_seconds_bucket{route=\"" << route << "\",le=\""
          << kBucketsS[i] << "\"} " << cumulative << "\n";
    }
    out << "reenact_http_request_duration_seconds_bucket{route=\"" << route
        << "\",le=\"+Inf\"} " << h.count << "\n"
        << "reenact_http_request_duration_seconds_sum{route=\"" << route << "\"} " << h.sum_s
        << "\n"
        << "reenact_http_request_duration_seconds_count{route=\"" << route << "\"} " << h.count
        << "\n";
  }
  out << "# HELP reenact_http_request_bytes_total Request body bytes received.\n"
      << "# TYPE reenact_http_request_bytes_total counter\n"
      << "reenact_http_request_bytes_total " << bytes_in_ << "\n"
      << "# HELP reenact_http_response_bytes_total Response body bytes sent.\n"
      << "# TYPE reenact_http_response_bytes_total counter\n"
      << "reenact_http_response_bytes_total " << bytes_out_ << "\n"
      << "# HELP reenact_clips Clips stored, by state.\n"
      << "# TYPE reenact_clips gauge\n"
      << "reenact_clips{state=\"draft\"} " << draft_clips << "\n"
      << "reenact_clips{state=\"published\"} " << published_clips << "\n";
  return out.str();
}

}  // namespace reenact::server
