#pragma once
// OpenNI2 for the whole process: initialised once, on first use, from any thread
// (openni::OpenNI::initialize is not safe to call concurrently; a function-local static
// serialises it), and never shut down (devices are closed by their owners; the library's
// own teardown at exit is enough).
//
// Where the drivers come from: Debian's libOpenNI2 (2.2.0.33+dfsg) reads its configuration
// from the fixed path /etc/openni2/OpenNI.ini and, unless that file sets [Drivers]
// Repository, loads every driver (libOniFile for .oni playback, libPS1080 for Kinect/Xtion,
// libPSLink) from "OpenNI2/Drivers" next to the library itself, i.e.
// /usr/lib/x86_64-linux-gnu/OpenNI2/Drivers. Neither depends on the working directory, so a
// program linked against the system library works from any cwd; OpenNiDriverDirectory() says
// where the loaded library looks, for error messages.
//
// Output: OpenNI2 logs to files or the console only as OpenNI.ini says (Debian: errors only,
// not to the console); console logging is switched off here as well so that nothing of it
// reaches our stdout. Drivers that print with printf (the PS1080 driver's USB warnings on
// some live devices) cannot be silenced through the API.

#include <string>

#include "common/error/expected.h"

namespace reenact::capture {

// Initialises OpenNI2 once per process; later calls return the first call's result. Error
// code "openni" with OpenNI2's own message and the driver directory if it fails.
Status InitializeOpenNi();

// The directory the loaded libOpenNI2 loads its drivers from by default:
// <directory of libOpenNI2.so>/OpenNI2/Drivers ("" if the library cannot be located).
std::string OpenNiDriverDirectory();

// OpenNI2's last extended error of this thread, trimmed to one line.
std::string OpenNiLastError();

}  // namespace reenact::capture
