// Pins what the bundled samples (data/) give at the defaults, bit for bit:
// the remesh, the encoded .srm file, and the meshes that files encoded by an
// earlier build decode to, at every level and from prefixes. A change that
// alters any of them on purpose updates the pin here and says in its commit
// why and by how much (bytes, dB).
#include <gtest/gtest.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::run_srcodec;
const auto q = test::shell_quote;

// FNV-1a, 64 bits: a pin, not a defence against anyone.
uint64_t fnv1a(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

uint64_t file_hash(const std::string& path) {
  StatusOr<std::string> bytes = read_file_bytes(path);
  EXPECT_TRUE(bytes.ok()) << bytes.status().message();
  return bytes.ok() ? fnv1a(bytes.value()) : 0;
}

struct Sample {
  const char* name;
  uint64_t srm_bytes;
  uint64_t srm_hash;     // `srcodec encode data/NAME.obj` at the defaults
  uint64_t remesh_hash;  // `srcodec remesh data/NAME.obj`, the OBJ it writes
};

const Sample kSamples[] = {
    {"spot", 2009, 0x4b40eb1e2aa113a2ull, 0xf00fcff0484c8ff2ull},
    {"bunny_npm", 1837, 0x832b597599b43f31ull, 0x4ead4481ebb8e5a0ull},
};

void PrintTo(const Sample& s, std::ostream* os) { *os << s.name; }

class SamplePin : public testing::TestWithParam<Sample> {};

TEST_P(SamplePin, EncodesToThePinnedFile) {
  const Sample& s = GetParam();
  test::ScratchDir dir;
  const std::string srm = dir.file("out.srm");
  auto e = run_srcodec("encode -q " + q(test::source_path(std::string("data/") + s.name + ".obj")) + " -o " + q(srm));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  StatusOr<std::string> bytes = read_file_bytes(srm);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_EQ(bytes->size(), s.srm_bytes);
  EXPECT_EQ(fnv1a(bytes.value()), s.srm_hash) << std::hex << fnv1a(bytes.value());
}

TEST_P(SamplePin, RemeshesToThePinnedMesh) {
  const Sample& s = GetParam();
  test::ScratchDir dir;
  const std::string obj = dir.file("out.obj");
  auto r = run_srcodec("remesh -q " + q(test::source_path(std::string("data/") + s.name + ".obj")) + " -o " + q(obj));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const uint64_t h = file_hash(obj);
  EXPECT_EQ(h, s.remesh_hash) << std::hex << h;
}

INSTANTIATE_TEST_SUITE_P(Bundled, SamplePin, testing::ValuesIn(kSamples),
                         [](const testing::TestParamInfo<Sample>& p) { return std::string(p.param.name); });

// tests/data/NAME_default.srm is `srcodec encode data/NAME.obj` at the
// defaults as an earlier build wrote it; these are the OBJ files it decodes
// to (the writer prints each coordinate's shortest exact text, so the hash
// pins every bit).
struct PinnedDecode {
  const char* name;
  const char* args;
  uint64_t hash;
};

const PinnedDecode kDecodes[] = {
    {"spot", "--level 0", 0x69b7d6383f9c92b9ull},
    {"spot", "--level 1", 0xd886545dd6b5b1b0ull},
    {"spot", "--level 2", 0x5a83c1fd023868c7ull},
    {"spot", "--level 3", 0xc38bac2a522722dfull},
    {"spot", "", 0x27c008682722ad43ull},
    {"spot", "--bytes 300", 0xefb9a6ce946893d5ull},
    {"spot", "--bytes 700", 0xd9be2d1e67d58eb6ull},
    {"spot", "--bytes 1200", 0x7bc93e831c6872a1ull},
    {"bunny_npm", "--level 0", 0xd53cc08ca5ff7279ull},
    {"bunny_npm", "--level 1", 0xa9f44d6d8f399bccull},
    {"bunny_npm", "--level 2", 0x84991db2054efa58ull},
    {"bunny_npm", "--level 3", 0x5489c8b9b57ded67ull},
    {"bunny_npm", "", 0x8c1c39ccafd760ebull},
    {"bunny_npm", "--bytes 300", 0xb3a10448aa625244ull},
    {"bunny_npm", "--bytes 700", 0x95f39eb4245d609dull},
    {"bunny_npm", "--bytes 1200", 0x529b411cb251a8ebull},
};

TEST(SamplePin, EarlierFilesDecodeToThePinnedMeshes) {
  test::ScratchDir dir;
  for (const PinnedDecode& d : kDecodes) {
    const std::string srm = test::source_path(std::string("tests/data/") + d.name + "_default.srm");
    const std::string obj = dir.file("out.obj");
    auto r = run_srcodec("decode " + q(srm) + " -o " + q(obj) + " " + d.args);
    ASSERT_EQ(r.exit_code, 0) << d.name << " " << d.args << ": " << r.err;
    const uint64_t h = file_hash(obj);
    EXPECT_EQ(h, d.hash) << d.name << " " << d.args << ": " << std::hex << h;
  }
}

}  // namespace
}  // namespace srcodec
