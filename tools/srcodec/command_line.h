// The srcodec program's command line: subcommands, each with required
// positional arguments, options bound to variables, flags and negated flags,
// checks on values, and generated help. Small on purpose: it supports what the
// commands use and needs nothing but the standard library, so that the
// decode-only program builds where only a compiler and Eigen are.
//
//   CommandLine cli("srcodec", "what it does", "srcodec 0.1.0");
//   Subcommand& decode = cli.add_command("decode", "Decode an .srm file");
//   decode.positional("file", input, "The .srm file");
//   decode.option("-o,--output", output, "Mesh to write").required();
//   decode.option("--level", level, "Level to decode").range(0, 12);
//   const ParseResult parsed = cli.parse(argc, argv);
//   if (parsed.command == nullptr) return parsed.exit_code;
//
// An error is one line on stderr, "srcodec decode: error: --level 13: must be
// in 0..12 (try srcodec decode --help)", and exit code kUsageError; --help and
// --version print to stdout and exit 0.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace srcodec {

// Distinct from 1, which the commands return when they fail at their work.
constexpr int kUsageError = 2;

namespace command_line_detail {
// Whole-text conversions; each returns what is wrong ("must be an integer"),
// or an empty string and sets `out`.
std::string parse_value(const std::string& text, int& out);
std::string parse_value(const std::string& text, unsigned long& out);
std::string parse_value(const std::string& text, unsigned long long& out);
std::string parse_value(const std::string& text, double& out);
std::string parse_value(const std::string& text, std::string& out);
std::string format_value(int value);
std::string format_value(unsigned long value);
std::string format_value(unsigned long long value);
std::string format_value(double value);
std::string format_value(const std::string& value);
std::string join(const std::vector<std::string>& parts, const std::string& separator);
// The placeholder of a value in help: INT, UINT, REAL, TEXT.
const char* value_name(const int*);
const char* value_name(const unsigned long*);
const char* value_name(const unsigned long long*);
const char* value_name(const double*);
const char* value_name(const std::string*);
}  // namespace command_line_detail

// One positional argument, option or flag of a subcommand. The subcommand
// owns it; references to it stay valid as long as the subcommand.
class Option {
 public:
  virtual ~Option() = default;
  Option(const Option&) = delete;
  Option& operator=(const Option&) = delete;

  // "--output" (the long name where there is one), "-q", or "MESH".
  const std::string& name() const { return name_; }
  bool positional() const { return positional_; }
  // Whether the command line gave it (a positional: whether it was there).
  bool given() const { return given_; }

 protected:
  // `names`: "-o,--output", "--json", or a positional's name ("mesh").
  Option(const std::string& names, std::string help);
  void set_required() { required_ = true; }
  void set_default_text(std::string text) { default_text_ = std::move(text); }
  void add_exclusion(Option& other);
  void add_need(Option& other) { needed_.push_back(&other); }
  void add_note(std::string note) { notes_.push_back(std::move(note)); }

 private:
  friend class Subcommand;
  virtual bool takes_value() const = 0;
  // A positional that takes every argument left (ListOption).
  virtual bool repeats() const { return false; }
  // Converts and checks `text` and stores it in the bound variable; returns
  // what is wrong with it, or an empty string. Flags get "".
  virtual std::string take(const std::string& text) = 0;
  virtual const char* value_placeholder() const = 0;
  std::string help_label() const;  // "-o, --output TEXT"
  std::string help_text() const;   // the description with its notes

  std::string name_, short_name_, long_name_, help_, default_text_;
  bool positional_ = false, required_ = false, given_ = false;
  std::vector<const Option*> excluded_, needed_;
  std::vector<std::string> notes_;     // from the checks: "0..12", "> 0", ...
  std::vector<std::string> not_with_;  // both sides of each exclusion
};

// The chainable calls every kind of option has; each returns the option
// itself, as its own type, so that checks can follow.
template <class Self>
class ChainedOption : public Option {
 public:
  Self& required() {
    set_required();
    return self();
  }
  // The two cannot be given together (either way round).
  Self& excludes(Option& other) {
    add_exclusion(other);
    return self();
  }
  // This one may be given only with `other`.
  Self& needs(Option& other) {
    add_need(other);
    return self();
  }

 protected:
  using Option::Option;

 private:
  Self& self() { return static_cast<Self&>(*this); }
};

// An option (or positional argument) with a value: "--levels 4",
// "--levels=4", "-o out.obj". T is int, size_t, uint64_t, double or
// std::string. Checks run in the order they were added; the first that
// fails names the error.
template <typename T>
class ValueOption final : public ChainedOption<ValueOption<T>> {
 public:
  ValueOption(const std::string& names, T& target, std::string help)
      : ChainedOption<ValueOption<T>>(names, std::move(help)), target_(target) {}

  // Help shows the variable's value at the time of this call as the default.
  ValueOption& show_default() {
    this->set_default_text(command_line_detail::format_value(target_));
    return *this;
  }
  ValueOption& range(T low, T high) {
    // Written so that NaN, which compares false, fails it.
    const std::string span = command_line_detail::format_value(low) + ".." + command_line_detail::format_value(high);
    return check([low, high](const T& x) { return low <= x && x <= high; }, "be in " + span, span);
  }
  ValueOption& positive() {
    return check([](const T& x) { return x > T{0}; }, "be positive", "> 0");
  }
  ValueOption& non_negative() {
    return check([](const T& x) { return x >= T{0}; }, "be non-negative", ">= 0");
  }
  // Sign and range checks let infinities through, and NaN reaches its
  // own error only here; every real option wants this first.
  ValueOption& finite() {
    static_assert(std::is_floating_point_v<T>, "finite() is for real numbers");
    return check([](const T& x) { return std::isfinite(x); }, "be a finite number", "");
  }
  ValueOption& one_of(const std::vector<T>& words) {
    std::vector<std::string> texts;
    for (const T& w : words) texts.push_back(command_line_detail::format_value(w));
    const std::string list = command_line_detail::join(texts, ", ");
    return check([words](const T& x) { return std::find(words.begin(), words.end(), x) != words.end(); },
                 "be one of " + list, "one of " + list);
  }
  // Any other check: `must` completes "must ..." in the error, `note` (if
  // not empty) goes into the help.
  ValueOption& check(std::function<bool(const T&)> accepts, std::string must, std::string note) {
    if (!note.empty()) this->add_note(note);
    checks_.push_back({std::move(accepts), std::move(must)});
    return *this;
  }

 private:
  struct Check {
    std::function<bool(const T&)> accepts;
    std::string must;
  };
  bool takes_value() const override { return true; }
  const char* value_placeholder() const override { return command_line_detail::value_name(&target_); }
  std::string take(const std::string& text) override {
    T value{};
    std::string problem = command_line_detail::parse_value(text, value);
    if (!problem.empty()) return problem;
    for (const Check& c : checks_)
      if (!c.accepts(value)) return "must " + c.must;
    target_ = value;
    return {};
  }

  T& target_;
  std::vector<Check> checks_;
};

// A flag sets its bool to `value_when_given`: true for "--json", false for a
// negated flag such as "--no-fit-surface".
class FlagOption final : public ChainedOption<FlagOption> {
 public:
  FlagOption(const std::string& names, bool& target, bool value_when_given, std::string help)
      : ChainedOption<FlagOption>(names, std::move(help)), target_(target), value_when_given_(value_when_given) {}

 private:
  bool takes_value() const override { return false; }
  const char* value_placeholder() const override { return ""; }
  std::string take(const std::string&) override {
    target_ = value_when_given_;
    return {};
  }

  bool& target_;
  bool value_when_given_;
};

// The last positional argument, taking every one left ("MESH..."): at
// least one, in the order given.
class ListOption final : public ChainedOption<ListOption> {
 public:
  ListOption(const std::string& name, std::vector<std::string>& target, std::string help)
      : ChainedOption<ListOption>(name, std::move(help)), target_(target) {}

 private:
  bool takes_value() const override { return true; }
  bool repeats() const override { return true; }
  const char* value_placeholder() const override { return "TEXT"; }
  std::string take(const std::string& text) override {
    target_.push_back(text);
    return {};
  }

  std::vector<std::string>& target_;
};

class Subcommand {
 public:
  Subcommand(std::string program, std::string name, std::string description);
  Subcommand(const Subcommand&) = delete;
  Subcommand& operator=(const Subcommand&) = delete;

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }

  // Positional arguments are required and taken in the order added.
  ValueOption<std::string>& positional(const std::string& name, std::string& target, std::string help) {
    return add(std::make_unique<ValueOption<std::string>>(name, target, std::move(help)), true).required();
  }
  // After every other positional: throws when one is added after it.
  ListOption& positional_list(const std::string& name, std::vector<std::string>& target, std::string help) {
    return add(std::make_unique<ListOption>(name, target, std::move(help)), true).required();
  }
  template <typename T>
  ValueOption<T>& option(const std::string& names, T& target, std::string help) {
    return add(std::make_unique<ValueOption<T>>(names, target, std::move(help)), false);
  }
  FlagOption& flag(const std::string& names, bool& target, std::string help) {
    return add(std::make_unique<FlagOption>(names, target, true, std::move(help)), false);
  }
  FlagOption& negated_flag(const std::string& names, bool& target, std::string help) {
    return add(std::make_unique<FlagOption>(names, target, false, std::move(help)), false);
  }

  // Parses the arguments that follow the command's name, once. Returns the
  // first error (without the program's prefix), or an empty string; sets
  // `help_asked` when -h or --help is among them (and then checks nothing).
  std::string parse(const std::vector<std::string>& args, bool& help_asked);
  std::string help() const;

 private:
  template <class O>
  O& add(std::unique_ptr<O> option, bool positional) {
    O& added = *option;
    adopt(std::move(option), positional);
    return added;
  }
  // Throws on a name used twice, or an option's name for a positional
  // argument (or the other way round).
  void adopt(std::unique_ptr<Option> option, bool positional);
  Option* find(const std::string& name) const;
  std::string give(Option& option, const std::string& text);
  // The option at args[i], with its value (moving i past it).
  std::string take_option(const std::vector<std::string>& args, size_t& i);
  std::string check_combination() const;
  std::string usage() const;

  std::string program_, name_, description_;
  std::vector<std::unique_ptr<Option>> options_;  // in the order added
  std::vector<Option*> positionals_;
};

struct ParseResult {
  const Subcommand* command = nullptr;  // the one to run; null when parsing ended the program
  int exit_code = 0;                    // when `command` is null: 0 after --help or --version
};

class CommandLine {
 public:
  CommandLine(std::string program, std::string description, std::string version);
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  Subcommand& add_command(const std::string& name, std::string description);

  // Parses once. Help and the version go to `out`, the error line to `err`.
  ParseResult parse(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
  ParseResult parse(int argc, const char* const* argv);  // to std::cout, std::cerr
  std::string help() const;

 private:
  ParseResult fail(const std::string& where, const std::string& problem, std::ostream& err) const;

  std::string program_, description_, version_;
  std::vector<std::unique_ptr<Subcommand>> commands_;
};

}  // namespace srcodec
