// The srcodec subcommands: each registers its options on the CLI11 app and
// runs as a function returning a Status (printed by main as one error line).
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>

#include "format/status.h"

namespace srcodec {

struct Command {
  CLI::App* app;              // the subcommand, to ask whether it was given
  std::function<Status()> run;  // runs it with the parsed options
};

Command add_info_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_draco_command(CLI::App& app);
Command add_remesh_command(CLI::App& app);
Command add_subdivide_command(CLI::App& app);
Command add_encode_command(CLI::App& app);
Command add_decode_command(CLI::App& app);
Command add_rd_command(CLI::App& app);

// For options taking a real number: CLI11's range and sign checks compare,
// and every comparison with NaN is false, so "nan" got past them (and "inf"
// past the sign checks). Strings that are not numbers are left to CLI11's
// own conversion error.
inline const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double x = std::strtod(text.c_str(), &end);
      if (end != text.c_str() && *end == '\0' && !std::isfinite(x)) return "not a finite number: " + text;
      return {};
    },
    "FINITE");

// `info` on an .srm file (srm_info.cpp).
Status print_srm_info(const std::string& path, bool json);

}  // namespace srcodec
