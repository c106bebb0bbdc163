// Decodes an .srm file twice: level 2 from all of it, and the best mesh its
// first 10 kB allow.   usage: decode FILE.srm
#include <srcodec/srcodec.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: decode FILE.srm\n"), 2;
  std::ifstream in(argv[1], std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  srcodec::DecodeOptions level2;
  level2.level = 2;
  srcodec::DecodeOptions first_10k;
  first_10k.max_bytes = 10000;
  for (const srcodec::DecodeOptions& options : {level2, first_10k}) {
    srcodec::StatusOr<srcodec::Decoded> d = srcodec::decode(bytes.data(), bytes.size(), options);
    if (!d.ok()) return std::fprintf(stderr, "%s\n", d.status().message().c_str()), 1;
    std::printf("level %d: %zu vertices, %zu triangles from %llu bytes\n", d->level, d->mesh.vertex_count(),
                d->mesh.triangle_count(), static_cast<unsigned long long>(d->bytes_used));
  }
  return 0;
}
