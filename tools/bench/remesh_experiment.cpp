// remesh_experiment: `srcodec remesh` with the switches that exist only for
// experiments (tools/remesh_experiments.py, tools/bench/*.py): --tolerance,
// the ablations --no-fit-surface, --no-untangle, --no-relax-slivers, and
// --unsplit-tangles. The paper's runs keep its positions with
// --no-fit-surface; the user's CLI has the defaults alone.
//
// usage: remesh_experiment remesh MESH -o OUT [srcodec remesh's options] [the switches above]
#include <iostream>
#include <new>

#include "tools/srcodec/commands.h"

int main(int argc, char** argv) {
  srcodec::CommandLine cli("remesh_experiment",
                           "srcodec remesh with the switches for experiments and ablations", "srcodec 0.1.0");
  const srcodec::Command remesh = srcodec::add_remesh_command(cli, /*experiment=*/true);
  const srcodec::ParseResult parsed = cli.parse(argc, argv);
  if (parsed.command == nullptr) return parsed.exit_code;
  try {
    const srcodec::Status status = remesh.run();
    if (!status.ok()) {
      std::cerr << "remesh_experiment remesh: error: " << status.message() << "\n";
      return 1;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << "remesh_experiment: error: out of memory\n";
    return 1;
  }
  return 0;
}
