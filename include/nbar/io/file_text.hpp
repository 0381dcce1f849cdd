// Reading a whole input file (a model, a task, a sketch, a curve) with a bound: a device or a
// pipe (/dev/zero, `yes |`) has no size to check first and no end, so the reader stops one byte
// past the limit instead of filling the memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <system_error>

namespace nbar::io {

// The largest model, task or drawing file the readers take.
inline constexpr std::size_t kMaxInputFileBytes = 16u << 20;

struct FileText {
  std::string text;       // the file, or its first `limit` bytes when too_long
  std::error_code error;  // it could not be opened or read (a folder included): text is empty
  bool too_long = false;  // it has more than `limit` bytes
};

FileText read_file_text(const std::filesystem::path& path, std::size_t limit = kMaxInputFileBytes);

// "the file has more than 16777216 bytes; nbar reads at most 16777216", for a FileText too_long.
std::string too_long_message(std::size_t limit = kMaxInputFileBytes);

}  // namespace nbar::io
