// Encodes a mesh file into the smallest .srm file that reaches a PSNR.
//   usage: encode MESH OUT.srm [PSNR_DB]   (default 60 dB)
#include <srcodec/srcodec.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

int main(int argc, char** argv) {
  if (argc < 3) return std::fprintf(stderr, "usage: encode MESH OUT.srm [PSNR_DB]\n"), 2;
  srcodec::StatusOr<srcodec::Mesh> mesh = srcodec::read_mesh(argv[1]);
  if (!mesh.ok()) return std::fprintf(stderr, "%s\n", mesh.status().message().c_str()), 1;

  srcodec::EncodeOptions options;
  options.rate = srcodec::Rate::psnr(argc > 3 ? std::atof(argv[3]) : 60.0);
  srcodec::EncodeReport report;
  srcodec::StatusOr<std::vector<uint8_t>> file = srcodec::encode(*mesh, options, &report);
  if (!file.ok()) return std::fprintf(stderr, "%s\n", file.status().message().c_str()), 1;

  std::ofstream(argv[2], std::ios::binary).write(reinterpret_cast<const char*>(file->data()), file->size());
  std::printf("%zu vertices -> %zu bytes, %.2f dB\n", mesh->vertex_count(), file->size(), report.psnr);
  return 0;
}
