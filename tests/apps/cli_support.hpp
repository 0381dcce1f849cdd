// Running the nbar program from the command-line tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nbar::cli_test {

struct CliRun {
  int code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs COMMAND with /bin/sh (popen), capturing its standard output and, through a temporary
// file, its standard error. COMMAND may be a list (`cd DIR && PROGRAM ARGS`): the standard
// error of all of it is captured.
inline CliRun run_shell(const std::string& command) {
  static int counter = 0;
  std::string err_name = "nbar_cli_test_";
  err_name.append(std::to_string(::getpid())).append("_").append(std::to_string(counter++)).append(".err");
  const std::filesystem::path err_file = std::filesystem::temp_directory_path() / err_name;
  const std::string shell_command = "( " + command + "\n) 2>" + err_file.string();
  CliRun run;
  FILE* pipe = ::popen(shell_command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file, std::ios::binary);
  std::stringstream ss;
  ss << err.rdbuf();
  run.err = ss.str();
  std::filesystem::remove(err_file);
  return run;
}

// Runs `nbar ARGS` through the shell (ARGS is quoted by the caller as needed).
inline CliRun nbar(const std::string& args) { return run_shell(std::string(NBAR_CLI_PATH).append(" ").append(args)); }

// A scratch directory for the files a test has nbar write, removed at the end of the test.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix)
      : dir_(std::filesystem::temp_directory_path() /
             (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(count_++))) {
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() { std::filesystem::remove_all(dir_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  static inline int count_ = 0;
  std::filesystem::path dir_;
};

// The whole of a file ("" when it cannot be read).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace nbar::cli_test
