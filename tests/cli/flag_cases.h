// Malformed values for every flag of a program, for the tests that try
// them (tests/cli/flags_test.cc for `animat`, tests/bench/tools_flags_test.cc
// for the developer tools): the flags a CLI11 --help lists, the values no
// flag of a type may take, and the check that a run refused one (exit 1 or
// 2 with a message, never a signal or an exception reaching terminate).
#ifndef ANIMAT_TESTS_CLI_FLAG_CASES_H_
#define ANIMAT_TESTS_CLI_FLAG_CASES_H_

#include <gtest/gtest.h>

#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/run_animat.h"

namespace animat::testing {

// `word` in single quotes for a POSIX shell.
inline std::string Quote(const std::string& word) {
  std::string out = "'";
  for (char c : word) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

// Each of `words` quoted, after a space.
inline std::string Join(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    line += ' ';
    line += Quote(word);
  }
  return line;
}

// A flag of a program: its long name, and the type of the value that
// follows it as the next word (CLI11's INT, UINT, FLOAT or TEXT), or ""
// when none does (a flag that takes no value, or a Google Benchmark flag,
// whose value is joined to it with '=').
struct Flag {
  std::string name;
  std::string type;
};

// The flags a CLI11 --help text lists, --help itself left out.
inline std::vector<Flag> FlagsInHelp(const std::string& help) {
  std::vector<Flag> flags;
  std::istringstream in(help);
  // "  -o,--output TEXT REQUIRED   ..." or "  --json    ..."
  const std::regex line(
      R"(^\s+(?:-\w,)?(--[\w-]+)(?: (INT|UINT|FLOAT|TEXT))?)");
  for (std::string text; std::getline(in, text);) {
    std::smatch m;
    if (std::regex_search(text, m, line) && m[1] != "--help") {
      flags.push_back({m[1], m[2]});
    }
  }
  return flags;
}

// The values no flag of CLI11 type `type` may take when it is INT, UINT or
// FLOAT (empty, not a number, beyond 64 bits, negative where unsigned, not
// finite); {} for another type, whose malformed values depend on what the
// flag names.
inline std::vector<std::string> MalformedNumbers(const std::string& type) {
  const std::string huge(5000, '9');
  if (type == "INT") return {"", "abc", "1.5", "1e999", huge, "-" + huge};
  if (type == "UINT") {
    return {"", "abc", "1.5", "1e999", huge, "-" + huge, "-1"};
  }
  if (type == "FLOAT") return {"", "abc", "nan", "inf", huge + "e999"};
  return {};
}

// `base` without `flag` (with the value word after it, if its type has
// one, or joined to it with '='), then `extra`: the flag's valid value
// gives way to the case's.
inline std::vector<std::string> WithCase(
    const std::vector<std::string>& base, const Flag& flag,
    const std::vector<std::string>& extra) {
  std::vector<std::string> words;
  for (size_t i = 0; i < base.size(); ++i) {
    if (base[i] == flag.name) {
      if (!flag.type.empty()) ++i;
      continue;
    }
    if (base[i].rfind(flag.name + "=", 0) == 0) continue;
    words.push_back(base[i]);
  }
  words.insert(words.end(), extra.begin(), extra.end());
  return words;
}

// Expects `run` to have refused its command line: exit 1 or 2, a message,
// no exception reaching terminate.
inline void ExpectRefused(const Outcome& run) {
  EXPECT_TRUE(run.exit_code == 1 || run.exit_code == 2)
      << "exit " << run.exit_code << ": " << run.output.substr(0, 500);
  EXPECT_FALSE(run.output.empty());
  EXPECT_EQ(run.output.find("terminate"), std::string::npos)
      << run.output.substr(0, 500);
}

// The malformed cases of a flag: each the words that replace its value in
// the base command line. None is a failure of the test (a flag whose
// value this test does not know).
using CasesOf =
    std::function<std::vector<std::vector<std::string>>(const Flag& flag)>;

// Runs build/bin/`program` `command` (a subcommand, or "") with `base`
// changed by each case of each of `flags`, and expects each refused.
inline void TryEveryCase(const std::string& program, const std::string& command,
                         const std::vector<std::string>& base,
                         const std::vector<Flag>& flags,
                         const CasesOf& cases_of) {
  ASSERT_FALSE(flags.empty()) << program << " " << command;
  for (const Flag& flag : flags) {
    const std::vector<std::vector<std::string>> cases = cases_of(flag);
    ASSERT_FALSE(cases.empty()) << program << " " << command << " " << flag.name
                                << " " << flag.type << ": no malformed values";
    for (const std::vector<std::string>& extra : cases) {
      std::string line = command + Join(WithCase(base, flag, extra));
      const Outcome run = RunTool(program, line);
      line = program + " " + line;
      if (line.size() > 200) line = line.substr(0, 200) + "...";
      SCOPED_TRACE(line);
      ExpectRefused(run);
    }
  }
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_CLI_FLAG_CASES_H_
