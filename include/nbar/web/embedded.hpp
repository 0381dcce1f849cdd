// Files built into the program (web/server/embed.cmake writes them into a generated source):
// the bundled example models and synthesis tasks, and the web app's static files (web/ui/).
// The server serves only these; it never opens a path a request names.
#pragma once

#include <span>
#include <string_view>

namespace nbar::web {

struct EmbeddedFile {
  std::string_view path;  // relative to its folder: "fourbar-crank-rocker.yaml", "synthesis/function-log10.yaml"
  std::string_view data;
};

std::span<const EmbeddedFile> example_files();  // examples/*.yaml and examples/synthesis/*.yaml
std::span<const EmbeddedFile> static_files();   // web/ui/

}  // namespace nbar::web
