#include "common/io/text_file.h"

#include <fstream>
#include <sstream>

namespace reenact {

Expected<std::string> ReadTextFile(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return MakeError("not_found", path.string() + ": no such " + std::string(what));
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) return MakeError("io", path.string() + ": cannot read the file");
  return text.str();
}

}  // namespace reenact
