// The server's connection guards as pure parts: per-address counts, the body memory budget,
// the minimum-rate deadline and the framing checks of RFC 9112.
#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "server/http/address_limiter.h"
#include "server/http/memory_budget.h"
#include "server/http/request_framing.h"
#include "server/http/transfer_deadline.h"

namespace reenact::server {
namespace {

using std::chrono::milliseconds;

TEST(AddressLimiter, CountsEachAddressAgainstItsOwnCap) {
  AddressLimiter limiter(2);
  EXPECT_TRUE(limiter.Acquire("10.0.0.1"));
  EXPECT_TRUE(limiter.Acquire("10.0.0.1"));
  EXPECT_FALSE(limiter.Acquire("10.0.0.1"));
  EXPECT_EQ(limiter.Held("10.0.0.1"), 2);  // a refusal counts nothing
  EXPECT_TRUE(limiter.Acquire("10.0.0.2"));
  limiter.Release("10.0.0.1");
  EXPECT_TRUE(limiter.Acquire("10.0.0.1"));
  limiter.Release("10.0.0.9");  // never acquired: ignored
  EXPECT_EQ(limiter.Held("10.0.0.9"), 0);
}

TEST(AddressLimiter, ZeroMeansNoLimit) {
  AddressLimiter limiter(0);
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(limiter.Acquire("a"));
  EXPECT_EQ(limiter.Held("a"), 1000);
}

TEST(MemoryBudget, ReservationsNeverExceedTheTotalAndGiveBackOnDestruction) {
  MemoryBudget budget(100);
  auto a = budget.TryReserve(60);
  ASSERT_TRUE(a.has_value());
  EXPECT_FALSE(budget.TryReserve(41).has_value());
  {
    auto b = budget.TryReserve(40);
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(budget.held(), 100u);
  }
  EXPECT_EQ(budget.held(), 60u);
  MemoryReservation moved = std::move(*a);
  EXPECT_EQ(budget.held(), 60u);  // a move hands the bytes over, not back
  moved.Release();
  moved.Release();  // twice is once
  EXPECT_EQ(budget.held(), 0u);
  EXPECT_FALSE(budget.TryReserve(101).has_value());
  EXPECT_FALSE(budget.TryReserve(SIZE_MAX).has_value());  // no overflow past the total
}

TEST(MemoryBudget, ConcurrentReservationsStayWithinTheTotal) {
  MemoryBudget budget(1000);
  std::atomic<size_t> peak{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 20000; ++i) {
        auto r = budget.TryReserve(300);
        if (!r) continue;
        size_t held = budget.held();
        size_t seen = peak.load();
        while (held > seen && !peak.compare_exchange_weak(seen, held)) {
        }
      }
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_LE(peak.load(), 1000u);
  EXPECT_EQ(budget.held(), 0u);
}

TEST(TransferDeadline, GraceThenRateThenCap) {
  const SteadyTime start{};
  const MinRate rate{1000.0, milliseconds(5000)};
  // Nothing moved yet: the grace alone.
  EXPECT_EQ(TransferDeadline(start, 0, rate, milliseconds(120000)), start + milliseconds(5000));
  // 2000 bytes moved buy 2 s more at 1000 B/s.
  EXPECT_EQ(TransferDeadline(start, 2000, rate, milliseconds(120000)), start + milliseconds(7000));
  // Never past the cap, however much moved.
  EXPECT_EQ(TransferDeadline(start, 1'000'000'000, rate, milliseconds(120000)),
            start + milliseconds(120000));
  // No rate rule: the cap.
  EXPECT_EQ(TransferDeadline(start, 0, MinRate{0.0, milliseconds(5000)}, milliseconds(30000)),
            start + milliseconds(30000));
}

TEST(TransferDeadline, OneByteEveryThreeSecondsFallsBehindWithinTenSeconds) {
  const MinRate rate{1024.0, milliseconds(5000)};
  const SteadyTime start{};
  uint64_t done = 0;
  SteadyTime now = start;
  while (now < TransferDeadline(start, done, rate, milliseconds(120000))) {
    now += milliseconds(3000);
    ++done;
  }
  EXPECT_LE(now - start, milliseconds(10000));
}

HeaderList With(std::initializer_list<std::pair<std::string, std::string>> fields) {
  HeaderList headers;
  for (const auto& [name, value] : fields) headers.emplace_back(name, value);
  return headers;
}

int StatusOf(const std::optional<Response>& refusal) { return refusal ? refusal->status : 0; }

TEST(RequestFraming, PlainChunkedAndContentLengthPass) {
  EXPECT_FALSE(FramingRefusal(11, With({{"Content-Length", "10"}})));
  EXPECT_FALSE(FramingRefusal(11, With({{"Transfer-Encoding", "chunked"}})));
  EXPECT_FALSE(FramingRefusal(11, With({{"transfer-encoding", " Chunked "}})));
  EXPECT_FALSE(FramingRefusal(10, With({})));
}

TEST(RequestFraming, AmbiguousOrUnknownTransferEncodingIs400) {
  EXPECT_EQ(StatusOf(FramingRefusal(
                11, With({{"Content-Length", "5"}, {"Transfer-Encoding", "chunked"}}))),
            400);
  EXPECT_EQ(StatusOf(FramingRefusal(11, With({{"Transfer-Encoding", "xchunked"}}))), 400);
  EXPECT_EQ(StatusOf(FramingRefusal(11, With({{"Transfer-Encoding", "chunked, gzip"}}))), 400);
  EXPECT_EQ(StatusOf(FramingRefusal(
                11, With({{"Transfer-Encoding", "chunked"}, {"Transfer-Encoding", "identity"}}))),
            400);
  EXPECT_EQ(StatusOf(FramingRefusal(10, With({{"Transfer-Encoding", "chunked"}}))), 400);
}

TEST(RequestFraming, CodingsBeforeChunkedAre501AndOtherVersions505) {
  EXPECT_EQ(StatusOf(FramingRefusal(11, With({{"Transfer-Encoding", "gzip, chunked"}}))), 501);
  EXPECT_EQ(StatusOf(FramingRefusal(20, With({}))), 505);
  EXPECT_EQ(StatusOf(FramingRefusal(9, With({}))), 505);
  EXPECT_FALSE(FramingRefusal(12, With({})));  // a later 1.x minor is read as 1.1
}

TEST(RequestFraming, ParserFailuresAre431ForHugeHeadersAnd400Otherwise) {
  EXPECT_EQ(MalformedRequest(true, "header limit exceeded").status, 431);
  const Response bad = MalformedRequest(false, "bad method");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.find("bad method"), std::string::npos);
}

}  // namespace
}  // namespace reenact::server
