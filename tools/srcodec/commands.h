// The srcodec subcommands: each registers its arguments and options on the
// command line and runs as a function returning a Status (printed by main as
// one error line).
#pragma once

#include <functional>
#include <string>

#include "format/status.h"
#include "tools/srcodec/command_line.h"

namespace srcodec {

struct Command {
  const Subcommand* cli;        // the subcommand, to know whether it was given
  std::function<Status()> run;  // runs it with the parsed options
};

Command add_info_command(CommandLine& cli);
Command add_compare_command(CommandLine& cli);
Command add_draco_command(CommandLine& cli);
// With `experiment`, also the switches that exist for experiments
// (add_experiment_flags): the benchmark program tools/bench/remesh_experiment.
Command add_remesh_command(CommandLine& cli, bool experiment = false);
Command add_subdivide_command(CommandLine& cli);
Command add_encode_command(CommandLine& cli);
Command add_decode_command(CommandLine& cli);
Command add_rd_command(CommandLine& cli);
Command add_render_command(CommandLine& cli);

// `info` on an .srm file (srm_info.cpp).
Status print_srm_info(const std::string& path, bool json);

}  // namespace srcodec
