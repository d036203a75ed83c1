#include "common/cli/command_line.h"

#include <gtest/gtest.h>

namespace reenact {
namespace {

const CommandLineSpec kSpec{{"out", "frames", "lat"}, {"headless"}};

TEST(CommandLine, ParsesPositionalsValuesAndSwitches) {
  const char* argv[] = {"prog", "record", "--out", "dir", "--headless", "--frames=12", "x"};
  const auto cl = CommandLine::Parse(7, argv, 1, kSpec);
  ASSERT_TRUE(cl.ok()) << cl.error().message;
  EXPECT_EQ(cl->positionals(), (std::vector<std::string>{"record", "x"}));
  EXPECT_EQ(*cl->Get("out"), "dir");
  EXPECT_TRUE(cl->Has("headless"));
  EXPECT_EQ(*cl->GetInt("frames", 0), 12);
  EXPECT_EQ(*cl->GetInt("missing", 7), 7);
}

TEST(CommandLine, UnknownFlagMissingValueAndBadNumberAreErrors) {
  const char* unknown[] = {"prog", "--bogus"};
  EXPECT_FALSE(CommandLine::Parse(2, unknown, 1, kSpec).ok());
  const char* missing[] = {"prog", "--out"};
  const auto r = CommandLine::Parse(2, missing, 1, kSpec);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("--out needs a value"), std::string::npos);
  const char* bad[] = {"prog", "--frames", "12x", "--lat", "abc"};
  const auto cl = CommandLine::Parse(5, bad, 1, kSpec);
  ASSERT_TRUE(cl.ok());
  EXPECT_FALSE(cl->GetInt("frames", 0).ok());
  EXPECT_FALSE(cl->RequireDouble("lat").ok());
  EXPECT_FALSE(cl->Require("out").ok());
}

TEST(CommandLine, LatLonValidatesRange) {
  EXPECT_EQ(*ParseLatLon("48.5,-11.25"), std::pair(48.5, -11.25));
  EXPECT_FALSE(ParseLatLon("91,0").ok());
  EXPECT_FALSE(ParseLatLon("10").ok());
  EXPECT_FALSE(ParseLatLon("a,b").ok());
  EXPECT_FALSE(ParseLatLon("10,181").ok());
}

}  // namespace
}  // namespace reenact
