#pragma once
// For the tests of reenact-eval's commands: run a command's own argument parser on
// `reenact-eval COMMAND ARGS...` as main() does, and check a refusal.

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/cli/command_line.h"
#include "common/error/expected.h"

namespace reenact::eval::cli_test {

// parse: the command's ParseXCommand(const CommandLine&); value_flags: its XFlags().
template <typename ParseCommand>
auto ParseEvalArgs(const std::string& command, const std::set<std::string>& value_flags,
                   ParseCommand parse, std::vector<std::string> args)
    -> decltype(parse(std::declval<const CommandLine&>())) {
  args.insert(args.begin(), {"reenact-eval", command});
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  auto cl = CommandLine::Parse(static_cast<int>(argv.size()), argv.data(), 1,
                               CommandLineSpec{value_flags, {}});
  if (!cl.ok()) return cl.error();
  return parse(*cl);
}

// The arguments were refused with this error code and a message that contains `says`.
template <typename T>
void ExpectRefused(const Expected<T>& parsed, const std::vector<std::string>& args,
                   const std::string& code, const std::string& says) {
  ASSERT_FALSE(parsed.ok()) << "accepted: " << ::testing::PrintToString(args);
  EXPECT_EQ(parsed.error().code, code) << parsed.error().message;
  EXPECT_NE(parsed.error().message.find(says), std::string::npos) << parsed.error().message;
}

}  // namespace reenact::eval::cli_test
