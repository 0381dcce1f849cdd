// Shared by the render tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace nbar::render::test_support {

// A directory for one test process's files, removed when the process ends.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& prefix) {
    std::string name = prefix;
    name += std::to_string(::getpid());
    path = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

// The shell-quoted form of a text.
inline std::string quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  out += '\'';
  return out;
}

// Runs a shell command; its exit code.
inline int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Headless Chromium, which scripts/install-deps.sh installs; empty when absent.
inline std::string chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (::access(path, X_OK) == 0) return path;
  return "";
}

// The start of a headless Chromium command line with its own profile directory (options and
// the page follow).
inline std::string browser_command(const std::string& browser, const std::filesystem::path& profile) {
  std::string c = "timeout 120 ";
  c += quote(browser);
  c += " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking"
       " --disable-component-update --disable-sync --disable-dev-shm-usage --user-data-dir=";
  c += quote(profile.string());
  return c;
}

}  // namespace nbar::render::test_support

// Without Chromium a browser test fails, unless NBAR_SKIP_BROWSER_TESTS=1 says to skip it.
#define REQUIRE_CHROMIUM(browser)                                                                   \
  const std::string browser = nbar::render::test_support::chromium();                               \
  if (browser.empty()) {                                                                            \
    const char* skip = std::getenv("NBAR_SKIP_BROWSER_TESTS");                                      \
    if (skip && std::string(skip) == "1")                                                           \
      GTEST_SKIP() << "\n*** Chromium is not installed (/usr/bin/chromium): the browser test is "   \
                      "NOT run. scripts/install-deps.sh installs it. ***\n";                        \
    FAIL() << "Chromium is not installed (/usr/bin/chromium): run scripts/install-deps.sh, or set " \
              "NBAR_SKIP_BROWSER_TESTS=1 to skip this test";                                        \
  }
