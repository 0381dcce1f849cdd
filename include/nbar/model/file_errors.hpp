// Messages about files that cannot be written, shared by every front-end.
#pragma once

#include <string>

namespace nbar {

// Why a file cannot be written, said the way a user can act on it: "cannot write out/a.csv:
// the folder 'out' does not exist", "... 'notes.txt' is a file, not a folder", or the system's
// reason. Call it right after the failed open or write (it reads errno).
std::string cannot_write_message(const std::string& path);

}  // namespace nbar
