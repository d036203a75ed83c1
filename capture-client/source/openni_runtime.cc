#include "capture-client/source/openni_runtime.h"

#include <OpenNI.h>
#include <dlfcn.h>

#include <filesystem>

namespace reenact::capture {

std::string OpenNiLastError() {
  std::string text = openni::OpenNI::getExtendedError();
  for (char& c : text)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  const size_t first = text.find_first_not_of(' ');
  const size_t last = text.find_last_not_of(' ');
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

std::string OpenNiDriverDirectory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&oniInitialize), &info) == 0 || info.dli_fname == nullptr)
    return "";
  std::error_code ec;
  const std::filesystem::path library = std::filesystem::canonical(info.dli_fname, ec);
  return ((ec ? std::filesystem::path(info.dli_fname) : library).parent_path() / "OpenNI2" /
          "Drivers")
      .string();
}

Status InitializeOpenNi() {
  static const Status status = []() -> Status {
    if (openni::OpenNI::initialize() != openni::STATUS_OK) {
      const std::string drivers = OpenNiDriverDirectory();
      return MakeError("openni",
                       "OpenNI2 failed to initialise (" + OpenNiLastError() +
                           "); it loads its drivers from " +
                           (drivers.empty() ? "OpenNI2/Drivers next to libOpenNI2" : drivers) +
                           ": install Debian's libopenni2-0 or check [Drivers] "
                           "Repository in /etc/openni2/OpenNI.ini");
    }
    openni::OpenNI::setLogConsoleOutput(false);
    return {};
  }();
  return status;
}

}  // namespace reenact::capture
