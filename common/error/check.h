#pragma once
// Broken preconditions are bugs: REENACT_CHECK throws CheckError naming the file and line.
// Expected failures of algorithms are values (std::optional, result structs); I/O and codec
// failures are Expected<T> (common/error/expected.h).

#include <stdexcept>
#include <string>

namespace reenact {

class CheckError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void ThrowCheckError(const char* file, int line, const char* condition,
                                  const std::string& message);

}  // namespace reenact

#define REENACT_CHECK(condition, message)                                            \
  do {                                                                               \
    if (!(condition)) ::reenact::ThrowCheckError(__FILE__, __LINE__, #condition, (message)); \
  } while (false)
