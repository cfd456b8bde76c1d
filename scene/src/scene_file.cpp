// The file-level checks of a scene file before it is parsed: a regular file of a
// sensible size, UTF-8, no tabs in the indentation.
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rheodda/scene/loader.hpp"

namespace rheodda::scene {

std::string read_scene_text(const std::string& path) {
  namespace fs = std::filesystem;
  // What is not a regular file of a sensible size is refused before it is read
  // (a folder, /dev/zero, a FIFO would hang or exhaust memory).
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw SceneError(path, {}, "", fmt::format("cannot open the scene file: {}",
                                               ec ? ec.message() : std::string("No such file or directory")));
  if (fs::is_directory(status)) throw SceneError(path, {}, "", "is a folder, not a scene file");
  if (!fs::is_regular_file(status))
    throw SceneError(path, {}, "", "is not a regular file (a device or a pipe?): give a YAML scene file");
  constexpr std::uintmax_t kMaxBytes = 64u << 20;
  const auto size = fs::file_size(path, ec);
  if (!ec && size > kMaxBytes)
    throw SceneError(path, {}, "",
                     fmt::format("is {} MB; scene files above {} MB are refused (describe large models with "
                                 "`grid` blocks)",
                                 size >> 20, kMaxBytes >> 20));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, {}, "", fmt::format("cannot open the scene file: {}", std::strerror(errno)));
  std::ostringstream buf;
  buf << in.rdbuf();
  std::string text = buf.str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw SceneError(path, {}, "", "the scene file is empty");
  // Encoding: UTF-8 (a UTF-8 byte-order mark is dropped); UTF-16/32 and Latin-1
  // are refused at the first byte that is not UTF-8, with its line and column.
  const auto b0 = text.empty() ? 0 : static_cast<unsigned char>(text[0]);
  const auto b1 = text.size() < 2 ? 0 : static_cast<unsigned char>(text[1]);
  if ((b0 == 0xFF && b1 == 0xFE) || (b0 == 0xFE && b1 == 0xFF))
    throw SceneError(path, {1, 1}, "", "the file is UTF-16 encoded: save the scene as UTF-8");
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
  int line = 1, column = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    // Well-formed UTF-8 (Unicode 15, table 3-7): no overlong forms, no surrogates, <= U+10FFFF.
    std::size_t len = c < 0x80 ? 1 : (c >= 0xC2 && c <= 0xDF) ? 2 : (c >= 0xE0 && c <= 0xEF) ? 3
                                                                  : (c >= 0xF0 && c <= 0xF4) ? 4 : 0;
    bool ok = len > 0 && i + len <= text.size();
    for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (ok && len > 2) {
      const auto c1 = static_cast<unsigned char>(text[i + 1]);
      ok = !((c == 0xE0 && c1 < 0xA0) || (c == 0xED && c1 >= 0xA0) || (c == 0xF0 && c1 < 0x90) ||
             (c == 0xF4 && c1 >= 0x90));
    }
    if (!ok || c == 0)
      throw SceneError(path, {line, column}, "",
                       c == 0 ? std::string("a NUL byte: this is not a text file (UTF-16? save the scene as UTF-8)")
                              : fmt::format("byte 0x{:02X} is not UTF-8 (a Latin-1 file?): save the scene as UTF-8", c));
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
    i += len;
  }
  // YAML indents with spaces only; yaml-cpp's message for a tab is "illegal map value".
  line = 1;
  for (std::size_t at = 0; at < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::size_t first = text.find_first_not_of(" \t", at);
    if (first != std::string::npos && first <= end) {
      // Within the line's indentation only: a search to the end of the file from every
      // line made this quadratic (100 s on a 93 000-line explicit rock mass).
      const auto indent_end = text.begin() + static_cast<std::ptrdiff_t>(first);
      const std::size_t tab = static_cast<std::size_t>(std::find(text.begin() + static_cast<std::ptrdiff_t>(at), indent_end, '\t') - text.begin());
      if (tab < first)
        throw SceneError(path, {line, static_cast<int>(tab - at) + 1}, "",
                         "a tab in the indentation: YAML indents with spaces only");
    }
    at = end + 1;
  }
  return text;
}

}  // namespace rheodda::scene
