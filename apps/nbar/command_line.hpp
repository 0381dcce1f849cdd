// The command line's parser as the commands see it: subcommands, their options and checks. CLI11
// (header-only, every function inline) is included by command_line.cpp alone, so that its
// functions are compiled once rather than in every command's unit; the names and the order of
// the calls are CLI11's, which writes the help and the messages exactly as before.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace nbar::cli {

// A check of an option's text: "" when it passes, else what is wrong with it. The description
// is what the help shows after the option's type ("POSITIVE"); empty, it shows none.
struct Check {
  std::function<std::string(std::string&)> test;
  std::string description;
  // When not empty, the text must be one of these words (CLI11's IsMember and its messages).
  std::vector<std::string> members;
};

inline Check one_of(std::vector<std::string> words) { return Check{{}, {}, std::move(words)}; }

// One option, flag or positional argument of a command.
class Option {
 public:
  explicit Option(CLI::Option* option) : option_(option) {}
  Option* required();
  Option* check(const Check& check);
  Option* group(const std::string& name);
  Option* delimiter(char separator);
  Option* type_name(const std::string& name);
  Option* expected(int count);
  // How many times it was given.
  std::size_t count() const;

 private:
  CLI::Option* option_;
};

// A command (nbar check, nbar solve...), or the program itself.
class Subcommand {
 public:
  explicit Subcommand(CLI::App* app) : app_(app) {}
  Subcommand(const Subcommand&) = delete;
  Subcommand& operator=(const Subcommand&) = delete;

  Option* add_option(const std::string& name, std::string& value, const std::string& help);
  Option* add_option(const std::string& name, int& value, const std::string& help);
  Option* add_option(const std::string& name, double& value, const std::string& help);
  Option* add_option(const std::string& name, std::optional<double>& value, const std::string& help);
  Option* add_option(const std::string& name, std::vector<std::string>& values, const std::string& help);
  Option* add_flag(const std::string& name, bool& value, const std::string& help);
  Subcommand* footer(const std::string& text);

  std::string name() const;
  bool parsed() const;

 protected:
  CLI::App* app() const { return app_; }

 private:
  Option* keep(CLI::Option* option);
  CLI::App* app_;
  std::deque<Option> options_;  // a deque: the pointers handed out stay valid
};

// The program: its commands, the version flag, the footer of its help, and the parse.
class CommandLine : public Subcommand {
 public:
  explicit CommandLine(const std::string& description);
  ~CommandLine();

  Subcommand* add_subcommand(const std::string& name, const std::string& description);
  void set_version_flag(const std::string& flag, const std::string& version);
  void require_subcommand(int count);
  std::vector<std::string> subcommand_names() const;

  // --lang, an option of the program and of every command (`nbar --lang es check` and
  // `nbar check --lang es` alike): its text when it was given, else nothing.
  std::optional<std::string> language_given() const;

  // Parses the arguments. When parsing ended the run (--help, --version or a usage error), CLI11
  // has printed what it prints and its exit code is returned; otherwise nothing.
  std::optional<int> parse(int argc, char** argv);

 private:
  void add_language_option(Subcommand& command);

  std::unique_ptr<CLI::App> owner_;
  std::deque<Subcommand> subcommands_;
  std::string language_;
  std::vector<Option*> language_options_;
};

}  // namespace nbar::cli
