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

}  // namespace nbar::cli_test
