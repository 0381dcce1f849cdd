// The command line's side of the request layer (nbar/request): each option of a request becomes
// a flag spelled in kebab-case, whose text is handed to the request as it was typed; the request
// checks it by the same rule as for the web API and Python. The command line adds nothing but
// the spelling and the format of its messages.
#pragma once

#include "command_line.hpp"

#include <initializer_list>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "nbar/request/options.hpp"

namespace nbar::cli {

// "--mesh-size" for "mesh_size".
inline std::string spell_flag(std::string_view key) { return request::flag_name(key); }

class RequestFlags {
 public:
  RequestFlags(Subcommand& command, const std::vector<request::OptionRule>& rules) : command_(command), rules_(rules) {}

  // Adds the options of these keys, in this order (the order of --help).
  RequestFlags& add(std::initializer_list<std::string_view> keys);
  Option* option(std::string_view key) const;

  // What was given on the command line, for the request to read.
  request::Options options() const;

 private:
  struct Given {
    Option* option = nullptr;
    request::OptionKind kind = request::OptionKind::Text;
    std::string text;
    std::vector<std::string> list;
    bool on = false;
  };
  Subcommand& command_;
  const std::vector<request::OptionRule>& rules_;
  std::map<std::string, std::unique_ptr<Given>, std::less<>> given_;
};

// Reads a request from the flags. A value its rule refuses is reported as CLI11 reports a bad
// option ("--order: must be from 0 to 5, not 9" and a hint), and false is returned.
template <class Request>
bool read_request(const RequestFlags& flags, Request& out) {
  try {
    out = Request::read(flags.options());
  } catch (const request::OptionError& e) {
    std::cerr << e.spelled(spell_flag) << "\nRun with --help for more information.\n";
    return false;
  }
  return true;
}

// An option's value refused once the model is known (a column, a traced point, a step):
// "error: --columns: no column matches ...".
inline void print_option_error(const request::OptionError& e) {
  std::cerr << "error: " << e.spelled(spell_flag) << '\n';
}

}  // namespace nbar::cli
