#pragma once
// How the command-line tools must fail on bad input: a non-zero exit, no hang, and one line
// of error text (a trailing newline allowed) that contains `needle`.

#include <gtest/gtest.h>

#include <string>

#include "tests/integration/process.h"

namespace reenact::testing {

inline void ExpectOneLineError(const ProcessResult& r, const std::string& needle) {
  EXPECT_FALSE(r.timed_out) << "hung";
  EXPECT_NE(r.exit_code, 0);
  std::string err = r.err;
  while (!err.empty() && err.back() == '\n') err.pop_back();
  EXPECT_EQ(err.find('\n'), std::string::npos) << "more than one line:\n" << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

}  // namespace reenact::testing
