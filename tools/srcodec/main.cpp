// srcodec: adaptive semi-regular wavelet mesh compression.
#include <iostream>
#include <vector>

#include "tools/srcodec/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"srcodec: wavelet mesh compression on adaptive semi-regular remeshes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("srcodec 0.1.0"));

  const std::vector<srcodec::Command> commands = {
      srcodec::add_info_command(app),
#if SRCODEC_WITH_MEASURE
      srcodec::add_compare_command(app),
      srcodec::add_draco_command(app),
      srcodec::add_remesh_command(app),
#endif
#if SRCODEC_WITH_ENCODER
      srcodec::add_subdivide_command(app),
#endif
#if SRCODEC_WITH_MEASURE
      srcodec::add_encode_command(app),
#endif
      srcodec::add_decode_command(app),
#if SRCODEC_WITH_MEASURE
      srcodec::add_rd_command(app),
#endif
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (const auto& command : commands) {
      if (!command.app->parsed()) continue;
      const srcodec::Status status = command.run();
      if (!status.ok()) {
        std::cerr << "srcodec " << command.app->get_name() << ": error: " << status.message() << "\n";
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
