#pragma once
// Reads a whole file for the parsers of imported text files (BVH motion, skeleton tracks).

#include <filesystem>
#include <string>
#include <string_view>

#include "common/error/expected.h"

namespace reenact {

// The file's bytes. Errors: "not_found" ("PATH: no such WHAT") when path is not a regular
// file, "io" when it cannot be read. what names the kind of file, e.g. "BVH file".
Expected<std::string> ReadTextFile(const std::filesystem::path& path, std::string_view what);

}  // namespace reenact
