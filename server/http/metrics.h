#pragma once
// Request metrics in the Prometheus text exposition format (version 0.0.4):
//   reenact_http_requests_total{route,status}      counter
//   reenact_http_request_duration_seconds{route}    histogram (handler + transfer time)
//   reenact_http_request_bytes_total                body bytes received
//   reenact_http_response_bytes_total               body bytes sent
//   reenact_clips{state="draft"|"published"}        gauge, read from the store at scrape time
// Thread-safe.

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>

namespace reenact::server {

class Metrics {
 public:
  // Upper bounds of the latency histogram's buckets, seconds (+Inf is implied).
  static constexpr std::array<double, 9> kBucketsS = {0.001, 0.0025, 0.005, 0.01, 0.025,
                                                      0.05,  0.1,    0.5,   2.5};

  // route: a pattern such as "PUT /v1/clips/{id}/frames/{n}" (never the raw path).
  void Record(const std::string& route, int status, double seconds, uint64_t bytes_in,
              uint64_t bytes_out);

  std::string Render(int64_t draft_clips, int64_t published_clips) const;

 private:
  struct Histogram {
    std::array<uint64_t, kBucketsS.size()> buckets{};  // non-cumulative counts
    uint64_t count = 0;
    double sum_s = 0.0;
  };

  mutable std::mutex mutex_;
  std::map<std::pair<std::string, int>, uint64_t> requests_;
  std::map<std::string, Histogram> latency_;
  uint64_t bytes_in_ = 0;
  uint64_t bytes_out_ = 0;
};

}  // namespace reenact::server
