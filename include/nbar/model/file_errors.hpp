// Messages about files that cannot be written, shared by every front-end.
#pragma once

#include <string>

namespace nbar {

// Why a file cannot be written, said the way a user can act on it: "cannot write out/a.csv:
// the folder 'out' does not exist", "... 'notes.txt' is a file, not a folder", or the system's
// reason. Call it right after the failed open or write (it reads errno).
std::string cannot_write_message(const std::string& path);

// The same reasons found before anything is written (a folder that does not exist, a file where
// the folder should be, a folder named as the file), so that a long computation is not run for
// an output that cannot be written; empty when the path may be written.
std::string output_path_problem(const std::string& path);

}  // namespace nbar
