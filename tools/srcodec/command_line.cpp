#include "tools/srcodec/command_line.h"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace srcodec {

namespace command_line_detail {
namespace {

// strtol and its kin skip leading blanks and stop at the first character
// they cannot use: a value must be a number from end to end.
bool whole(const std::string& text, const char* end) {
  return !text.empty() && !std::isspace(static_cast<unsigned char>(text[0])) && end == text.c_str() + text.size();
}

template <typename U>
std::string parse_unsigned(const std::string& text, U& out) {
  // strtoull would read "-1" as the largest value.
  if (!text.empty() && text[0] == '-') return "must be a non-negative integer";
  errno = 0;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (!whole(text, end)) return "must be a non-negative integer";
  if (errno == ERANGE || value > std::numeric_limits<U>::max())
    return "must be at most " + std::to_string(std::numeric_limits<U>::max());
  out = static_cast<U>(value);
  return {};
}

}  // namespace

std::string parse_value(const std::string& text, int& out) {
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (!whole(text, end)) return "must be an integer";
  if (errno == ERANGE || value < INT_MIN || value > INT_MAX)
    return "must be an integer from " + std::to_string(INT_MIN) + " to " + std::to_string(INT_MAX);
  out = static_cast<int>(value);
  return {};
}

std::string parse_value(const std::string& text, unsigned long& out) { return parse_unsigned(text, out); }
std::string parse_value(const std::string& text, unsigned long long& out) { return parse_unsigned(text, out); }

std::string parse_value(const std::string& text, double& out) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (!whole(text, end)) return "must be a number";
  // Overflow reads as an infinity: finite() is the check that refuses it.
  out = value;
  return {};
}

std::string parse_value(const std::string& text, std::string& out) {
  out = text;
  return {};
}

std::string format_value(int value) { return std::to_string(value); }
std::string format_value(unsigned long value) { return std::to_string(value); }
std::string format_value(unsigned long long value) { return std::to_string(value); }
std::string format_value(const std::string& value) { return value; }

// The shortest text that reads back as the same number: "0.01", not
// "0.010000000000000000208"; and "300", not "3e+02".
std::string format_value(double value) {
  const bool plain = std::fabs(value) >= 1e-4 && std::fabs(value) < 1e15;
  char text[40];
  for (int digits = 1;; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (digits >= std::numeric_limits<double>::max_digits10) return text;
    if (std::strtod(text, nullptr) == value && !(plain && std::strchr(text, 'e'))) return text;
  }
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : separator) + part;
  return text;
}

const char* value_name(const int*) { return "INT"; }
const char* value_name(const unsigned long*) { return "UINT"; }
const char* value_name(const unsigned long long*) { return "UINT"; }
const char* value_name(const double*) { return "REAL"; }
const char* value_name(const std::string*) { return "TEXT"; }

}  // namespace command_line_detail

namespace {

constexpr size_t kHelpWidth = 80;
// Labels wider than this put their description on the next line.
constexpr size_t kMaxHelpColumn = 30;

// "-5" and "-inf" are values (of --threshold, say), not options.
bool looks_like_option(const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return false;
  double number;
  return !command_line_detail::parse_value(arg, number).empty();
}

bool is_help(const std::string& arg) { return arg == "-h" || arg == "--help"; }

// Appends `start` (a label, maybe empty) and then `text` word-wrapped to
// kHelpWidth, its lines starting at `column`.
void append_wrapped(std::string& out, std::string start, const std::string& text, size_t column) {
  std::string line = std::move(start);
  if (!line.empty() && line.size() + 2 > column) {
    out += line + "\n";
    line.clear();
  }
  line.resize(column, ' ');
  bool line_has_words = false;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (line_has_words && line.size() + 1 + word.size() > kHelpWidth) {
      out += line + "\n";
      line.assign(column, ' ');
      line_has_words = false;
    }
    if (line_has_words) line += ' ';
    line += word;
    line_has_words = true;
  }
  line.erase(line.find_last_not_of(' ') + 1);
  out += line + "\n";
}

// Where descriptions start: past the indent, the widest label and a gap.
size_t help_column(size_t widest_label) { return std::min(2 + widest_label + 2, kMaxHelpColumn); }

std::string quoted_if_empty(const std::string& text) { return text.empty() ? "''" : text; }

}  // namespace

Option::Option(const std::string& names, std::string help) : help_(std::move(help)) {
  std::istringstream list(names);
  for (std::string n; std::getline(list, n, ',');) {
    const bool is_long = n.size() > 2 && n.compare(0, 2, "--") == 0 && std::isalpha(static_cast<unsigned char>(n[2]));
    const bool is_short = n.size() == 2 && n[0] == '-' && std::isalpha(static_cast<unsigned char>(n[1]));
    if (is_long && long_name_.empty()) {
      long_name_ = n;
    } else if (is_short && short_name_.empty()) {
      short_name_ = n;
    } else if (names.find(',') == std::string::npos && !n.empty() && std::isalpha(static_cast<unsigned char>(n[0]))) {
      positional_ = true;
      for (char c : n) name_ += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    } else {
      throw std::invalid_argument("bad option names \"" + names + "\"");
    }
  }
  if (!positional_) name_ = long_name_.empty() ? short_name_ : long_name_;
}

void Option::add_exclusion(Option& other) {
  excluded_.push_back(&other);  // one side is enough: the check looks at every option given
  not_with_.push_back(other.name());
  other.not_with_.push_back(name());
}

std::string Option::help_label() const {
  if (positional_) return repeats() ? name_ + "..." : name_;
  std::string label = short_name_.empty() ? "    " : short_name_ + (long_name_.empty() ? "" : ", ");
  label += long_name_;
  if (takes_value()) label += std::string(" ") + value_placeholder();
  return label;
}

std::string Option::help_text() const {
  std::vector<std::string> notes;
  if (required_ && !positional_) notes.push_back("required");  // every positional is
  if (!default_text_.empty()) notes.push_back("default: " + default_text_);
  notes.insert(notes.end(), notes_.begin(), notes_.end());
  if (!not_with_.empty()) notes.push_back("not with " + command_line_detail::join(not_with_, ", "));
  std::vector<std::string> needed;
  for (const Option* o : needed_) needed.push_back(o->name());
  if (!needed.empty()) notes.push_back("needs " + command_line_detail::join(needed, ", "));
  return notes.empty() ? help_ : help_ + " [" + command_line_detail::join(notes, "; ") + "]";
}

Subcommand::Subcommand(std::string program, std::string name, std::string description)
    : program_(std::move(program)), name_(std::move(name)), description_(std::move(description)) {}

void Subcommand::adopt(std::unique_ptr<Option> option, bool positional) {
  if (option->positional_ != positional)
    throw std::invalid_argument(name_ + ": " + option->name_ + (positional ? " is an option's name" : " has no dash"));
  for (const std::string* n : {&option->short_name_, &option->long_name_, &option->name_}) {
    if (n->empty()) continue;
    if (is_help(*n) || find(*n) != nullptr) throw std::logic_error(name_ + ": " + *n + " is added twice");
  }
  if (option->positional_ && !positionals_.empty() && positionals_.back()->repeats())
    throw std::logic_error(name_ + ": " + option->name_ + " follows " + positionals_.back()->name_ + "...");
  if (option->positional_) positionals_.push_back(option.get());
  options_.push_back(std::move(option));
}

Option* Subcommand::find(const std::string& name) const {
  for (const auto& o : options_)
    if (o->short_name_ == name || o->long_name_ == name || (o->positional_ && o->name_ == name)) return o.get();
  return nullptr;
}

std::string Subcommand::give(Option& option, const std::string& text) {
  if (option.given_ && option.takes_value() && !option.repeats()) return option.name() + " is given more than once";
  const std::string problem = option.take(text);
  if (!problem.empty()) return option.name() + " " + quoted_if_empty(text) + ": " + problem;
  option.given_ = true;
  return {};
}

std::string Subcommand::take_option(const std::vector<std::string>& args, size_t& i) {
  const std::string& arg = args[i];
  // "--level=3"; a short option's value is always the next argument.
  const size_t equals = arg.compare(0, 2, "--") == 0 ? arg.find('=') : std::string::npos;
  const std::string name = arg.substr(0, equals);
  Option* option = find(name);
  if (option == nullptr || option->positional_) return "unknown option " + name;
  if (!option->takes_value()) return equals == std::string::npos ? give(*option, "") : name + " takes no value";
  if (equals != std::string::npos) return give(*option, arg.substr(equals + 1));
  if (i + 1 == args.size() || looks_like_option(args[i + 1]))
    return option->name() + " needs a value (" + option->value_placeholder() + ")";
  return give(*option, args[++i]);
}

std::string Subcommand::parse(const std::vector<std::string>& args, bool& help_asked) {
  // Help wins over every error: it is what a puzzled user asks for.
  for (const std::string& arg : args) {
    if (arg == "--") break;
    if (is_help(arg)) {
      help_asked = true;
      return {};
    }
  }
  size_t next_positional = 0;
  bool only_positionals = false;  // after "--"
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    std::string problem;
    if (!only_positionals && arg == "--") {
      only_positionals = true;
    } else if (only_positionals || !looks_like_option(arg)) {
      if (next_positional == positionals_.size()) return "unexpected argument " + quoted_if_empty(arg);
      Option& positional = *positionals_[next_positional];
      if (!positional.repeats()) ++next_positional;
      problem = give(positional, arg);
    } else {
      problem = take_option(args, i);
    }
    if (!problem.empty()) return problem;
  }
  return check_combination();
}

std::string Subcommand::check_combination() const {
  for (const auto& o : options_)
    if (o->required_ && !o->given_) return o->name() + (o->positional_ ? " is missing" : " is required");
  for (const auto& o : options_) {
    if (!o->given_) continue;
    for (const Option* other : o->excluded_)
      if (other->given_) return o->name() + " and " + other->name() + " cannot be given together";
    for (const Option* other : o->needed_)
      if (!other->given_) return o->name() + " needs " + other->name();
  }
  return {};
}

std::string Subcommand::usage() const {
  std::string line = "Usage: " + program_ + " " + name_;
  bool optional = false;
  for (const auto& o : options_) {
    if (o->positional_) {
      line += " " + o->help_label();
    } else if (o->required_) {
      line += " " + o->name() + " " + o->value_placeholder();
    } else {
      optional = true;
    }
  }
  return optional ? line + " [options]" : line;
}

std::string Subcommand::help() const {
  const std::string help_label = "-h, --help";
  size_t widest = help_label.size();
  for (const auto& o : options_) widest = std::max(widest, o->help_label().size());
  const size_t column = help_column(widest);
  std::string out;
  append_wrapped(out, "", usage(), 0);
  out += "\n";
  append_wrapped(out, "", description_, 0);
  if (!positionals_.empty()) {
    out += "\nArguments:\n";
    for (const Option* p : positionals_) append_wrapped(out, "  " + p->help_label(), p->help_text(), column);
  }
  out += "\nOptions:\n";
  append_wrapped(out, "  " + help_label, "Print this help and exit", column);
  for (const auto& o : options_)
    if (!o->positional_) append_wrapped(out, "  " + o->help_label(), o->help_text(), column);
  return out;
}

CommandLine::CommandLine(std::string program, std::string description, std::string version)
    : program_(std::move(program)), description_(std::move(description)), version_(std::move(version)) {}

Subcommand& CommandLine::add_command(const std::string& name, std::string description) {
  for (const auto& c : commands_)
    if (c->name() == name) throw std::logic_error("command " + name + " is added twice");
  commands_.push_back(std::make_unique<Subcommand>(program_, name, std::move(description)));
  return *commands_.back();
}

ParseResult CommandLine::fail(const std::string& where, const std::string& problem, std::ostream& err) const {
  err << where << ": error: " << problem << " (try " << where << " --help)\n";
  return {nullptr, kUsageError};
}

ParseResult CommandLine::parse(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  if (args.empty()) return fail(program_, "no command given", err);
  const std::string& first = args.front();
  if (is_help(first)) {
    out << help();
    return {};
  }
  if (first == "--version") {
    out << version_ << "\n";
    return {};
  }
  Subcommand* command = nullptr;
  for (const auto& c : commands_)
    if (c->name() == first) command = c.get();
  if (command == nullptr)
    return fail(program_, (looks_like_option(first) ? "unknown option " : "unknown command ") + first, err);
  bool help_asked = false;
  const std::string problem = command->parse({args.begin() + 1, args.end()}, help_asked);
  if (help_asked) {
    out << command->help();
    return {};
  }
  if (!problem.empty()) return fail(program_ + " " + command->name(), problem, err);
  return {command, 0};
}

ParseResult CommandLine::parse(int argc, const char* const* argv) {
  return parse(std::vector<std::string>(argv + std::min(argc, 1), argv + argc), std::cout, std::cerr);
}

std::string CommandLine::help() const {
  size_t widest = std::string("    --version").size();
  for (const auto& c : commands_) widest = std::max(widest, c->name().size());
  const size_t column = help_column(widest);
  std::string out;
  append_wrapped(out, "", description_, 0);
  out += "\n";
  append_wrapped(out, "", "Usage: " + program_ + " COMMAND [arguments] [options]", 0);
  out += "\nCommands:\n";
  for (const auto& c : commands_) append_wrapped(out, "  " + c->name(), c->description(), column);
  out += "\nOptions:\n";
  append_wrapped(out, "  -h, --help", "Print this help and exit", column);
  append_wrapped(out, "      --version", "Print the version and exit", column);
  out += "\n";
  append_wrapped(out, "", program_ + " COMMAND --help lists a command's arguments and options.", 0);
  return out;
}

}  // namespace srcodec
