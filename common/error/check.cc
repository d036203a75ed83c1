#include "common/error/check.h"

namespace reenact {

void ThrowCheckError(const char* file, int line, const char* condition,
                     const std::string& message) {
  throw CheckError(std::string(file) + ":" + std::to_string(line) + ": check failed: " +
                   condition + (message.empty() ? "" : ": " + message));
}

}  // namespace reenact
