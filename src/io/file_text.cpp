#include "nbar/io/file_text.hpp"

#include <cerrno>
#include <fstream>

namespace nbar::io {

FileText read_file_text(const std::filesystem::path& path, std::size_t limit) {
  FileText out;
  // A directory opens without error on Linux and then reads as empty.
  std::error_code status;
  if (std::filesystem::is_directory(path, status)) {
    out.error = std::make_error_code(std::errc::is_a_directory);
    return out;
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    out.error = std::error_code(errno != 0 ? errno : EIO, std::generic_category());
    return out;
  }
  constexpr std::size_t kChunk = 1u << 16;
  while (out.text.size() <= limit) {
    const std::size_t have = out.text.size();
    out.text.resize(have + kChunk);
    in.read(out.text.data() + have, static_cast<std::streamsize>(kChunk));
    out.text.resize(have + static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  if (in.bad()) {
    out.text.clear();
    out.error = std::make_error_code(std::errc::io_error);
    return out;
  }
  if (out.text.size() > limit) {
    out.text.resize(limit);
    out.too_long = true;
  }
  return out;
}

std::string too_long_message(std::size_t limit) {
  return "the file has more than " + std::to_string(limit) + " bytes; nbar reads at most " + std::to_string(limit);
}

}  // namespace nbar::io
