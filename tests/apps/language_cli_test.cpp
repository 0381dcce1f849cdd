// The command line's language: --lang, else NBAR_LANG, else English; never LANG or LC_*, so that
// scripts and the golden tests keep English unless they ask (tests/golden/ holds the --lang cases).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "apps/cli_support.hpp"

namespace nbar::cli_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kSyntaxError = std::string(NBAR_SOURCE_DIR) + "/tests/golden/inputs/syntax-error.yaml";

// `nbar check` of a model with a YAML error, with the environment given before the program.
CliRun check_with(const std::string& environment, const std::string& options = "") {
  return run_shell("env -u NBAR_LANG " + environment + " " + NBAR_CLI_PATH + " check " + kSyntaxError + options);
}

TEST(CliLanguage, NbarLangAsksForSpanishTheFileItsPlaceKept) {
  const CliRun run = check_with("NBAR_LANG=es");
  EXPECT_EQ(run.code, 1);
  EXPECT_EQ(run.err, "error: " + kSyntaxError + ":7:7: YAML no válido: este '[' no se cierra nunca con un ']'\n");
}

TEST(CliLanguage, TheOptionOverTheEnvironment) {
  const CliRun run = check_with("NBAR_LANG=es", " --lang en");
  EXPECT_EQ(run.code, 1);
  EXPECT_THAT(run.err, HasSubstr(":7:7: invalid YAML: this '[' is never closed by a ']'"));
}

TEST(CliLanguage, EnglishUnlessAskedWhateverTheLocale) {
  for (const char* locale : {"LANG=es_ES.UTF-8", "LC_ALL=es_ES.UTF-8 LC_MESSAGES=es_ES.UTF-8", "LANGUAGE=es", ""}) {
    const CliRun run = check_with(locale);
    EXPECT_EQ(run.code, 1) << locale;
    EXPECT_THAT(run.err, HasSubstr("invalid YAML")) << locale;
    EXPECT_THAT(run.err, Not(HasSubstr("no válido"))) << locale;
  }
  // An empty NBAR_LANG is as if it were not set.
  EXPECT_THAT(check_with("NBAR_LANG=").err, HasSubstr("invalid YAML"));
}

TEST(CliLanguage, ALanguageNbarDoesNotSpeakIsABadOptionNamedWhereItCameFrom) {
  const CliRun flag = check_with("", " --lang xx");
  EXPECT_EQ(flag.code, 2);
  EXPECT_EQ(flag.err,
            "--lang: the language 'xx' is not one nbar speaks: use en or es\nRun with --help for more information.\n");
  const CliRun environment = check_with("NBAR_LANG=fr");
  EXPECT_EQ(environment.code, 2);
  EXPECT_THAT(environment.err, HasSubstr("NBAR_LANG: the language 'fr' is not one nbar speaks: use en or es"));
  // Before or after the command, with a region: the same option.
  EXPECT_EQ(run_shell(std::string(NBAR_CLI_PATH) + " --lang es-ES check " + kSyntaxError).err,
            check_with("NBAR_LANG=es").err);
}

}  // namespace
}  // namespace nbar::cli_test
