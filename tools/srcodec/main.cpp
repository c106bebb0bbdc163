// srcodec: adaptive semi-regular wavelet mesh compression.
#include <iostream>
#include <vector>

#include "tools/srcodec/commands.h"

int main(int argc, char** argv) {
  srcodec::CommandLine cli("srcodec", "srcodec: wavelet mesh compression on adaptive semi-regular remeshes",
                           "srcodec 0.1.0");

  const std::vector<srcodec::Command> commands = {
      srcodec::add_info_command(cli),
#if SRCODEC_WITH_MEASURE
      srcodec::add_compare_command(cli),
      srcodec::add_draco_command(cli),
#endif
#if SRCODEC_WITH_ENCODER
      srcodec::add_remesh_command(cli),
      srcodec::add_subdivide_command(cli),
      srcodec::add_encode_command(cli),
#endif
      srcodec::add_decode_command(cli),
#if SRCODEC_WITH_MEASURE
      srcodec::add_rd_command(cli),
      srcodec::add_render_command(cli),
#endif
  };

  const srcodec::ParseResult parsed = cli.parse(argc, argv);
  if (parsed.command == nullptr) return parsed.exit_code;  // help, version, or a usage error already printed
  try {
    for (const auto& command : commands) {
      if (command.cli != parsed.command) continue;
      const srcodec::Status status = command.run();
      if (!status.ok()) {
        std::cerr << "srcodec " << command.cli->name() << ": error: " << status.message() << "\n";
        return 1;
      }
    }
  } catch (const std::bad_alloc&) {
    std::cerr << "srcodec: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "srcodec: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
