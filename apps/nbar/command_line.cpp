// The one unit that includes CLI11 (command_line.hpp says why).
#include "command_line.hpp"

#include <CLI/CLI.hpp>

namespace nbar::cli {

Option* Option::required() {
  option_->required();
  return this;
}

Option* Option::check(const Check& check) {
  if (!check.members.empty())
    option_->check(CLI::IsMember(check.members));
  else
    option_->check(CLI::Validator(check.test, check.description));
  return this;
}

Option* Option::group(const std::string& name) {
  option_->group(name);
  return this;
}

Option* Option::delimiter(char separator) {
  option_->delimiter(separator);
  return this;
}

Option* Option::type_name(const std::string& name) {
  option_->type_name(name);
  return this;
}

Option* Option::expected(int count) {
  option_->expected(count);
  return this;
}

std::size_t Option::count() const { return option_->count(); }

Option* Subcommand::keep(CLI::Option* option) { return &options_.emplace_back(option); }

Option* Subcommand::add_option(const std::string& name, std::string& value, const std::string& help) {
  return keep(app_->add_option(name, value, help));
}

Option* Subcommand::add_option(const std::string& name, int& value, const std::string& help) {
  return keep(app_->add_option(name, value, help));
}

Option* Subcommand::add_option(const std::string& name, double& value, const std::string& help) {
  return keep(app_->add_option(name, value, help));
}

Option* Subcommand::add_option(const std::string& name, std::optional<double>& value, const std::string& help) {
  return keep(app_->add_option(name, value, help));
}

Option* Subcommand::add_option(const std::string& name, std::vector<std::string>& values, const std::string& help) {
  return keep(app_->add_option(name, values, help));
}

Option* Subcommand::add_flag(const std::string& name, bool& value, const std::string& help) {
  return keep(app_->add_flag(name, value, help));
}

Subcommand* Subcommand::footer(const std::string& text) {
  app_->footer(text);
  return this;
}

std::string Subcommand::name() const { return app_->get_name(); }

bool Subcommand::parsed() const { return app_->parsed(); }

CommandLine::CommandLine(const std::string& description) : Subcommand(new CLI::App(description)), owner_(app()) {
  add_language_option(*this);
}

// Checked after the parse by request::read_language, which refuses a language as the web API does.
void CommandLine::add_language_option(Subcommand& command) {
  language_options_.push_back(
      command.add_option("--lang", language_, "the language of the messages: en or es (default: $NBAR_LANG, else en)")
          ->type_name("TEXT:{en,es}"));
}

std::optional<std::string> CommandLine::language_given() const {
  for (const Option* option : language_options_)
    if (option->count() > 0) return language_;
  return std::nullopt;
}

CommandLine::~CommandLine() = default;

Subcommand* CommandLine::add_subcommand(const std::string& name, const std::string& description) {
  Subcommand& command = subcommands_.emplace_back(app()->add_subcommand(name, description));
  add_language_option(command);
  return &command;
}

void CommandLine::set_version_flag(const std::string& flag, const std::string& version) {
  app()->set_version_flag(flag, version);
}

void CommandLine::require_subcommand(int count) { app()->require_subcommand(count); }

std::vector<std::string> CommandLine::subcommand_names() const {
  std::vector<std::string> names;
  for (const CLI::App* sub : app()->get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

std::optional<int> CommandLine::parse(int argc, char** argv) {
  try {
    app()->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app()->exit(e);
  }
  return std::nullopt;
}

}  // namespace nbar::cli
