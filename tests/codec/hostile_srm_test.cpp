// Hostile .srm files (issue: untrusted input): every cut, random mutations,
// counts at their limits, empty and future files. Each must end with a clear
// error or a valid mesh, quickly, and never crash.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "codec/srm_codec.h"
#include "format/byte_io.h"
#include "format/checksum.h"
#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

std::vector<uint8_t> golden() {
  const std::string s = read_file_bytes(test::source_path("tests/data/golden_v1.srm")).value();
  return std::vector<uint8_t>(s.begin(), s.end());
}

// Parses and decodes; returns whether a mesh came out. Fails the test if it
// took more than a second.
bool try_decode(const std::vector<uint8_t>& bytes, int level = -1) {
  const auto start = std::chrono::steady_clock::now();
  bool ok = false;
  SrmReadOptions read;
  read.max_level = level;
  StatusOr<SrmFile> f = parse_srm(bytes.data(), bytes.size(), read);
  if (f.ok()) {
    DecodeOptions options;
    options.level = level;
    options.max_vertices = 200000;
    StatusOr<DecodedSrm> d = decode_srm(f.value(), options);
    ok = d.ok();
    if (!ok) {
      EXPECT_FALSE(d.status().message().empty());
    }
  } else {
    EXPECT_FALSE(f.status().message().empty());
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  return ok;
}

TEST(HostileSrm, EveryCutOfTheGoldenFile) {
  const std::vector<uint8_t> file = golden();
  const SrmFile whole = parse_srm(file.data(), file.size()).value();
  // From the end of the header on, every prefix decodes (inside the base
  // mesh, to the base triangles before the cut).
  const uint64_t decodable = whole.header_size;
  for (size_t n = 0; n <= file.size(); ++n) {
    const std::vector<uint8_t> cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_EQ(try_decode(cut), n >= decodable) << n;
  }
}

TEST(HostileSrm, AThousandSeededMutations) {
  const std::vector<uint8_t> file = golden();
  std::mt19937 rng(2026);
  int meshes = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    std::vector<uint8_t> b = file;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < edits; ++k) b[rng() % b.size()] = static_cast<uint8_t>(rng());
    meshes += try_decode(b, trial % 3 == 0 ? 1 : -1);
  }
  // Checksums catch nearly every mutation; those that pass must be harmless.
  EXPECT_LT(meshes, 100);
}

TEST(HostileSrm, HeaderCountsAtTheirLimitsWithValidChecksums) {
  const std::vector<uint8_t> file = golden();
  const SrmFile whole = parse_srm(file.data(), file.size()).value();
  std::vector<std::vector<uint8_t>> flags, segments;
  for (const auto& c : whole.flags) flags.push_back(c.bytes);
  for (const auto& c : whole.segments) segments.push_back(c.bytes);
  const uint64_t huge = uint64_t{1} << 62;
  for (int field = 0; field < 5; ++field) {
    SrmHeader h = whole.header;
    if (field == 0) h.base_vertices = h.level_vertices[0] = huge;
    if (field == 1) h.base_triangles = huge;
    if (field == 2) h.level_vertices.back() = huge;
    if (field == 3) h.input_vertices = huge;
    if (field == 4) h.quant_step = 1e30;
    const std::vector<uint8_t> bytes = write_srm(h, whole.base.bytes, flags, segments);
    // Counts that size the decoder's work are refused; the input's vertex
    // count (the bpv denominator) and a wild but finite step are harmless.
    EXPECT_EQ(try_decode(bytes), field >= 3) << field;
  }
}

TEST(HostileSrm, EmptyFutureAndPaddedFiles) {
  EXPECT_FALSE(try_decode({}));
  std::vector<uint8_t> future = golden();
  future[4] = 2;
  StatusOr<SrmFile> f = parse_srm(future.data(), future.size());
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(f.status().message().find("version 2"), std::string::npos) << f.status().message();
  std::vector<uint8_t> padded = golden();
  padded.push_back(0);
  f = parse_srm(padded.data(), padded.size());
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.status().message().find("after its last chunk"), std::string::npos) << f.status().message();
}

}  // namespace
}  // namespace srcodec
