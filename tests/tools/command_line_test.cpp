// The command-line parser on its own: values, checks, flags, combinations,
// errors and help, without running the srcodec program.
#include "tools/srcodec/command_line.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace srcodec {
namespace {

// Every kind of option the srcodec commands use, on one command "run".
class TestProgram {
 public:
  std::string input, output, second, word = "alpha";
  int level = -1, shift = 0;
  size_t samples = 100;
  uint64_t bytes = 0;
  double ratio = 1.5, weight = 0.0, loss = 0.0, deepen = 0.0;
  bool json = false, fit = true, uniform = false, exact = false;

  explicit TestProgram(bool two_positionals = false) {
    Subcommand& run = cli.add_command("run", "Run something on a mesh");
    run.positional("input", input, "The input");
    if (two_positionals) run.positional("second", second, "Another input");
    run.option("-o,--output", output, "Where to write").required();
    run.option("--level", level, "Level").range(0, 12);
    run.option("--shift", shift, "Any integer");
    run.option("--samples", samples, "Samples").range(size_t{1000}, size_t{100000000}).show_default();
    run.option("--bytes", bytes, "Bytes").positive();
    run.option("--ratio", ratio, "Ratio").finite().range(0.25, 64.0).show_default();
    auto& weight_option = run.option("--weight", weight, "Weight").finite().non_negative();
    run.flag("--uniform", uniform, "Uniform").excludes(weight_option);
    run.flag("--exact", exact, "Exact").excludes(weight_option);
    auto& loss_option = run.option("--loss", loss, "Loss").range(0.01, 60.0);
    run.option("--deepen", deepen, "Deepen").finite().range(0.0, 1.0).needs(loss_option);
    run.option("--word", word, "A word").one_of({"alpha", "beta"}).show_default();
    run.flag("--json", json, "Print JSON");
    run.negated_flag("--no-fit", fit, "Do not fit");
    cli.add_command("other", "Another command");
  }

  struct Outcome {
    ParseResult result;
    std::string out, err;
    bool ok() const { return result.command != nullptr && result.exit_code == 0 && err.empty(); }
    // A usage error: one line on err naming the problem and pointing at --help.
    testing::AssertionResult failed_with(const std::string& words) const {
      if (result.command == nullptr && result.exit_code == kUsageError && out.empty() &&
          err.find(words) != std::string::npos && err.find("--help") != std::string::npos &&
          std::count(err.begin(), err.end(), '\n') == 1 && err.back() == '\n')
        return testing::AssertionSuccess();
      return testing::AssertionFailure() << "exit code " << result.exit_code << ", err \"" << err << "\", out \""
                                         << out << "\", expected an error with \"" << words << "\"";
    }
  };

  Outcome parse(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    Outcome o;
    o.result = cli.parse(args, out, err);
    o.out = out.str();
    o.err = err.str();
    return o;
  }
  // "run IN -o OUT" followed by `more`.
  Outcome run(const std::vector<std::string>& more) {
    std::vector<std::string> args = {"run", "in.obj", "-o", "out.obj"};
    args.insert(args.end(), more.begin(), more.end());
    return parse(args);
  }

  CommandLine cli{"prog", "prog: a program to test the parser", "prog 1.2.3"};
};

// A fresh program refuses `args` (run_refused: after "run in.obj -o out.obj")
// with a usage error containing `words`.
testing::AssertionResult parse_refused(const std::vector<std::string>& args, const std::string& words) {
  TestProgram p;
  return p.parse(args).failed_with(words);
}
testing::AssertionResult run_refused(const std::vector<std::string>& more, const std::string& words) {
  TestProgram p;
  return p.run(more).failed_with(words);
}

TEST(CommandLine, BindsValuesOfEveryType) {
  TestProgram p;
  const auto r = p.run({"--level", "3", "--shift", "-7", "--samples", "5000", "--bytes", "18446744073709551615",
                        "--ratio", "0.5", "--weight", "2.25", "--word", "beta"});
  ASSERT_TRUE(r.ok()) << r.err;
  EXPECT_EQ(r.result.command->name(), "run");
  EXPECT_EQ(p.input, "in.obj");
  EXPECT_EQ(p.output, "out.obj");
  EXPECT_EQ(p.level, 3);
  EXPECT_EQ(p.shift, -7);  // a negative number is a value, not an option
  EXPECT_EQ(p.samples, 5000u);
  EXPECT_EQ(p.bytes, UINT64_MAX);
  EXPECT_EQ(p.ratio, 0.5);
  EXPECT_EQ(p.weight, 2.25);
  EXPECT_EQ(p.word, "beta");
}

TEST(CommandLine, OptionsNotGivenKeepTheirValues) {
  TestProgram p;
  ASSERT_TRUE(p.run({}).ok());
  EXPECT_EQ(p.level, -1);
  EXPECT_EQ(p.samples, 100u);  // a default need not pass the checks: they judge what the user gives
  EXPECT_EQ(p.ratio, 1.5);
  EXPECT_EQ(p.word, "alpha");
  EXPECT_FALSE(p.json);
  EXPECT_TRUE(p.fit);
}

TEST(CommandLine, TakesEqualsFormsAndOptionsAnywhere) {
  TestProgram p;
  const auto r = p.parse({"run", "--level=4", "--output=o.ply", "in.obj", "--ratio=2", "--word="});
  EXPECT_FALSE(r.ok());  // "--word=" gives the empty word, which is not one of alpha, beta
  EXPECT_TRUE(r.failed_with("--word '': must be one of alpha, beta")) << r.err;

  TestProgram q;
  ASSERT_TRUE(q.parse({"run", "--level=4", "--output=o.ply", "in.obj", "--ratio=2"}).ok());
  EXPECT_EQ(q.level, 4);
  EXPECT_EQ(q.output, "o.ply");
  EXPECT_EQ(q.input, "in.obj");
  EXPECT_EQ(q.ratio, 2.0);
}

TEST(CommandLine, DoubleDashEndsTheOptions) {
  TestProgram p;
  ASSERT_TRUE(p.parse({"run", "-o", "out.obj", "--", "--json"}).ok());
  EXPECT_EQ(p.input, "--json");
  EXPECT_FALSE(p.json);
}

TEST(CommandLine, FlagsAndNegatedFlags) {
  TestProgram p;
  ASSERT_TRUE(p.run({"--json", "--no-fit", "--json"}).ok());  // a flag may repeat
  EXPECT_TRUE(p.json);
  EXPECT_FALSE(p.fit);
  EXPECT_TRUE(run_refused({"--json=true"}, "--json takes no value"));
}

TEST(CommandLine, RefusesTextThatIsNotANumber) {
  for (const char* text : {"x", "3x", " 3", "3.5", ""}) {
    TestProgram p;
    EXPECT_TRUE(p.run({"--level=" + std::string(text)}).failed_with("must be an integer")) << text;
    EXPECT_EQ(p.level, -1) << "a refused value is not stored";
  }
  EXPECT_TRUE(run_refused({"--shift", "99999999999"}, "--shift 99999999999: must be an integer from"));
  EXPECT_TRUE(run_refused({"--samples", "-3000"}, "--samples -3000: must be a non-negative integer"));
  EXPECT_TRUE(run_refused({"--bytes", "18446744073709551616"}, "--bytes 18446744073709551616: must be at most"));
  EXPECT_TRUE(run_refused({"--ratio", "2,5"}, "--ratio 2,5: must be a number"));
}

TEST(CommandLine, RangesIncludeTheirEnds) {
  TestProgram p;
  ASSERT_TRUE(p.run({"--level", "0", "--samples", "100000000", "--ratio", "64"}).ok());
  EXPECT_EQ(p.level, 0);
  EXPECT_EQ(p.samples, 100000000u);
  EXPECT_TRUE(run_refused({"--level", "13"}, "--level 13: must be in 0..12"));
  EXPECT_TRUE(run_refused({"--samples", "999"}, "--samples 999: must be in 1000..100000000"));
  EXPECT_TRUE(run_refused({"--ratio", "0.2"}, "--ratio 0.2: must be in 0.25..64"));
  EXPECT_TRUE(run_refused({"--loss", "nan"}, "--loss nan: must be in 0.01..60"))
      << "a range refuses NaN even without finite()";
}

TEST(CommandLine, SignChecks) {
  EXPECT_TRUE(run_refused({"--bytes", "0"}, "--bytes 0: must be positive"));
  TestProgram q;
  ASSERT_TRUE(q.run({"--bytes", "1", "--weight", "0"}).ok());
  EXPECT_EQ(q.bytes, 1u);
  EXPECT_TRUE(run_refused({"--weight", "-0.5"}, "--weight -0.5: must be non-negative"));
}

TEST(CommandLine, FiniteRefusesNanAndInfinities) {
  for (const char* text : {"nan", "inf", "-inf", "infinity", "1e999"}) {
    TestProgram p;
    EXPECT_TRUE(p.run({"--weight", text}).failed_with("--weight " + std::string(text) + ": must be a finite number"))
        << text;
    EXPECT_EQ(p.weight, 0.0) << text;
  }
}

TEST(CommandLine, AllowedWords) {
  TestProgram p;
  EXPECT_TRUE(p.run({"--word", "gamma"}).failed_with("--word gamma: must be one of alpha, beta"));
  EXPECT_EQ(p.word, "alpha");
  TestProgram q;
  ASSERT_TRUE(q.run({"--word", "beta"}).ok());
  EXPECT_EQ(q.word, "beta");
}

TEST(CommandLine, ExcludedPairs) {
  EXPECT_TRUE(run_refused({"--uniform", "--weight", "1"}, "cannot be given together"));
  TestProgram q;  // either way round
  const auto r = q.run({"--weight", "1", "--uniform"});
  EXPECT_TRUE(r.failed_with("cannot be given together")) << r.err;
  EXPECT_NE(r.err.find("--uniform"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--weight"), std::string::npos) << r.err;
  EXPECT_TRUE(run_refused({"--exact", "--weight", "1"}, "--exact and --weight cannot be given together"));
  TestProgram alone;
  ASSERT_TRUE(alone.run({"--uniform", "--exact"}).ok()) << "exclusions do not chain";
  EXPECT_TRUE(alone.uniform);
  EXPECT_TRUE(alone.exact);
}

TEST(CommandLine, NeededOptions) {
  EXPECT_TRUE(run_refused({"--deepen", "0.5"}, "--deepen needs --loss"));
  TestProgram q;
  ASSERT_TRUE(q.run({"--deepen", "0.5", "--loss", "1"}).ok());
  EXPECT_EQ(q.deepen, 0.5);
  TestProgram r;
  EXPECT_TRUE(r.run({"--loss", "1"}).ok()) << "the need goes one way";
}

TEST(CommandLine, RequiredOptionsAndArguments) {
  EXPECT_TRUE(parse_refused({"run", "in.obj"}, "--output is required"));
  EXPECT_TRUE(parse_refused({"run", "-o", "out.obj"}, "INPUT is missing"));
  TestProgram two(/*two_positionals=*/true);
  EXPECT_TRUE(two.run({}).failed_with("SECOND is missing"));
  TestProgram both(/*two_positionals=*/true);
  ASSERT_TRUE(both.run({"b.obj"}).ok());
  EXPECT_EQ(both.second, "b.obj");
}

TEST(CommandLine, UnknownAndMisplacedArguments) {
  EXPECT_TRUE(run_refused({"--bogus"}, "unknown option --bogus"));
  EXPECT_TRUE(run_refused({"--bogus=3"}, "unknown option --bogus"));
  EXPECT_TRUE(run_refused({"extra.obj"}, "unexpected argument extra.obj"));
  EXPECT_TRUE(run_refused({"--level", "1", "--level", "2"}, "--level is given more than once"));
}

TEST(CommandLine, MissingValues) {
  EXPECT_TRUE(run_refused({"--level"}, "--level needs a value"));
  TestProgram q;
  EXPECT_TRUE(q.run({"--level", "--json"}).failed_with("--level needs a value"));
  EXPECT_FALSE(q.json);
  EXPECT_TRUE(parse_refused({"run", "in.obj", "-o"}, "--output needs a value"));
}

TEST(CommandLine, ProgramLevelErrors) {
  EXPECT_TRUE(parse_refused({}, "no command given"));
  EXPECT_TRUE(parse_refused({"frobnicate"}, "unknown command frobnicate"));
  EXPECT_TRUE(parse_refused({"--json"}, "unknown option --json"));
}

TEST(CommandLine, ErrorsNameTheProgramOrCommand) {
  TestProgram p;
  const auto none = p.parse({});
  EXPECT_EQ(none.err, "prog: error: no command given (try prog --help)\n");
  TestProgram q;
  const auto bad = q.run({"--level", "13"});
  EXPECT_EQ(bad.err, "prog run: error: --level 13: must be in 0..12 (try prog run --help)\n");
}

TEST(CommandLine, OnlyTheCommandGivenIsChosen) {
  TestProgram p;
  const auto r = p.parse({"other"});
  ASSERT_TRUE(r.ok()) << r.err;
  EXPECT_EQ(r.result.command->name(), "other");
  EXPECT_EQ(p.input, "");
}

TEST(CommandLine, VersionAndProgramHelp) {
  TestProgram p;
  const auto version = p.parse({"--version"});
  EXPECT_EQ(version.result.command, nullptr);
  EXPECT_EQ(version.result.exit_code, 0);
  EXPECT_EQ(version.out, "prog 1.2.3\n");
  EXPECT_TRUE(version.err.empty());
  for (const char* help : {"--help", "-h"}) {
    TestProgram q;
    const auto h = q.parse({help});
    EXPECT_EQ(h.result.command, nullptr);
    EXPECT_EQ(h.result.exit_code, 0);
    EXPECT_TRUE(h.err.empty());
    EXPECT_EQ(h.out.rfind("prog: a program to test the parser\n", 0), 0u) << h.out;
    EXPECT_NE(h.out.find("\n  run    "), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("Run something on a mesh"), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("\n  other  "), std::string::npos) << h.out;
    EXPECT_NE(h.out.find("--version"), std::string::npos) << h.out;
  }
}

TEST(CommandLine, CommandHelp) {
  TestProgram p;
  // Help wins over the errors around it: it is what a puzzled user asks for.
  const auto h = p.parse({"run", "--level", "99", "--help", "--bogus"});
  EXPECT_EQ(h.result.command, nullptr);
  EXPECT_EQ(h.result.exit_code, 0);
  EXPECT_TRUE(h.err.empty()) << h.err;
  EXPECT_EQ(h.out.rfind("Usage: prog run INPUT --output TEXT [options]\n", 0), 0u) << h.out;
  for (const std::string line : {"  INPUT ", "  -h, --help ", "  -o, --output TEXT ", "      --level INT ",
                                  "      --samples UINT ", "      --ratio REAL ", "      --json ", "      --no-fit "})
    EXPECT_NE(h.out.find("\n" + line), std::string::npos) << line << " in\n" << h.out;
  for (const std::string note : {"Where to write [required]", "Level [0..12]",
                                  "Samples [default: 100; 1000..100000000]", "Ratio [default: 1.5; 0.25..64]",
                                  "Bytes [> 0]", "Weight [>= 0; not with --uniform, --exact]", "Uniform [not with --weight]",
                                  "Deepen [0..1; needs --loss]", "A word [default: alpha; one of alpha, beta]"})
    EXPECT_NE(h.out.find(note), std::string::npos) << note << " in\n" << h.out;
  EXPECT_EQ(p.level, -1) << "nothing is stored when help is asked";
}

TEST(CommandLine, HelpWrapsLongDescriptions) {
  std::string text;
  CommandLine cli("prog", "prog", "1");
  Subcommand& cmd = cli.add_command("run", "Run");
  std::string words;
  for (int i = 0; i < 40; ++i) words += "word" + std::to_string(i) + " ";
  cmd.option("--a-rather-long-option-name", text, words);
  cmd.option("--b", text, words);
  const std::string help = cmd.help();
  std::istringstream lines(help);
  size_t count = 0;
  for (std::string line; std::getline(lines, line); ++count) EXPECT_LE(line.size(), 80u) << line;
  EXPECT_GT(count, 10u);
  // The long name overflows the label column: its description starts below it.
  EXPECT_NE(help.find("      --a-rather-long-option-name TEXT\n"), std::string::npos) << help;
  EXPECT_NE(help.find("word0 word1"), std::string::npos);
  EXPECT_NE(help.find("word39"), std::string::npos);
}

TEST(CommandLine, MistakesInTheProgramThrow) {
  CommandLine cli("prog", "prog", "1");
  Subcommand& cmd = cli.add_command("run", "Run");
  std::string text;
  cmd.option("-o,--output", text, "");
  EXPECT_THROW(cmd.option("--output", text, ""), std::logic_error);
  EXPECT_THROW(cmd.option("-o", text, ""), std::logic_error);
  EXPECT_THROW(cmd.option("--help", text, ""), std::logic_error);
  EXPECT_THROW(cmd.option("output", text, ""), std::invalid_argument);
  EXPECT_THROW(cmd.positional("--input", text, ""), std::invalid_argument);
  EXPECT_THROW(cmd.option("-output", text, ""), std::invalid_argument);
  EXPECT_THROW(cmd.option("--", text, ""), std::invalid_argument);
  EXPECT_THROW(cli.add_command("run", "again"), std::logic_error);
}

TEST(CommandLine, APositionalListTakesEveryArgumentLeft) {
  CommandLine cli("prog", "prog", "1");
  Subcommand& cmd = cli.add_command("show", "Show meshes");
  std::string first, output;
  std::vector<std::string> rest;
  cmd.positional("first", first, "The first");
  cmd.positional_list("more", rest, "The others");
  cmd.option("-o,--output", output, "Where");
  std::string extra;
  EXPECT_THROW(cmd.positional("extra", extra, ""), std::logic_error);
  std::ostringstream out, err;
  ASSERT_NE(cli.parse({"show", "a.obj", "b.obj", "-o", "x.png", "c.obj", "--", "-d.obj"}, out, err).command, nullptr)
      << err.str();
  EXPECT_EQ(first, "a.obj");
  EXPECT_EQ(rest, (std::vector<std::string>{"b.obj", "c.obj", "-d.obj"}));
  EXPECT_NE(cmd.help().find("Usage: prog show FIRST MORE... [options]"), std::string::npos) << cmd.help();
  EXPECT_NE(cmd.help().find("  MORE..."), std::string::npos) << cmd.help();

  CommandLine none("prog", "prog", "1");
  Subcommand& cmd2 = none.add_command("show", "Show meshes");
  std::vector<std::string> meshes;
  cmd2.positional_list("mesh", meshes, "Meshes");
  std::ostringstream out2, err2;
  EXPECT_EQ(none.parse({"show"}, out2, err2).command, nullptr);
  EXPECT_NE(err2.str().find("MESH is missing"), std::string::npos) << err2.str();
}

TEST(CommandLine, GivenTellsWhatTheUserGave) {
  CommandLine cli("prog", "prog", "1");
  Subcommand& cmd = cli.add_command("run", "Run");
  int levels = 4, other = 0;
  const Option& levels_option = cmd.option("--levels", levels, "Levels").show_default();
  const Option& other_option = cmd.option("--other", other, "Other");
  std::ostringstream out, err;
  ASSERT_NE(cli.parse({"run", "--levels", "4"}, out, err).command, nullptr) << err.str();
  EXPECT_TRUE(levels_option.given()) << "given, even with the default's value";
  EXPECT_FALSE(other_option.given());
}

}  // namespace
}  // namespace srcodec
