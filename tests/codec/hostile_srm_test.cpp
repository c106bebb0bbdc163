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

// The golden file of .srm version 1 or 2 (raw planes), or the sample of
// version 3 (creases).
std::vector<uint8_t> golden(int version = 1) {
  const std::string name = version == 3 ? "creases_v3" : "golden_v" + std::to_string(version);
  const std::string s = read_file_bytes(test::source_path("tests/data/" + name + ".srm")).value();
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
    SrmDecodeOptions options;
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
  for (int version : {1, 2, 3}) {
    const std::vector<uint8_t> file = golden(version);
    const SrmFile whole = parse_srm(file.data(), file.size()).value();
    // From the end of the header on, every prefix decodes (inside the base
    // mesh, to the base triangles before the cut).
    const uint64_t decodable = whole.header_size;
    for (size_t n = 0; n <= file.size(); ++n) {
      const std::vector<uint8_t> cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
      EXPECT_EQ(try_decode(cut), n >= decodable) << version << " " << n;
    }
  }
}

TEST(HostileSrm, AThousandSeededMutations) {
  for (int version : {1, 2, 3}) {
    const std::vector<uint8_t> file = golden(version);
    std::mt19937 rng(2026);
    int meshes = 0;
    for (int trial = 0; trial < 1000; ++trial) {
      std::vector<uint8_t> b = file;
      const int edits = 1 + static_cast<int>(rng() % 8);
      for (int k = 0; k < edits; ++k) b[rng() % b.size()] = static_cast<uint8_t>(rng());
      meshes += try_decode(b, trial % 3 == 0 ? 1 : -1);
    }
    // Checksums catch nearly every mutation; those that pass must be harmless.
    EXPECT_LT(meshes, 100) << version;
  }
}

// Version 2's raw plane count, rewritten with a valid checksum: 1..31 decode
// (a wrong count gives a wrong mesh, not a crash), 0 and 32 are refused. And
// raw segments of random bytes with valid checksums decode safely.
TEST(HostileSrm, RawPlaneCountsAndRawSegmentsWithValidChecksums) {
  const std::vector<uint8_t> file = golden(2);
  const SrmFile whole = parse_srm(file.data(), file.size()).value();
  ASSERT_EQ(whole.header.raw_planes, 2);
  std::vector<std::vector<uint8_t>> flags, segments;
  for (const auto& c : whole.flags) flags.push_back(c.bytes);
  for (const auto& c : whole.segments) segments.push_back(c.bytes);
  for (int raw : {1, 3, 13, kSrmMaxPlane + 1}) {
    SrmHeader h = whole.header;
    h.raw_planes = raw;
    EXPECT_TRUE(try_decode(write_srm(h, whole.base.bytes, flags, segments))) << raw;
  }
  // The count is the byte after the top plane's; find it by writing one.
  const std::vector<uint8_t> bytes = write_srm(whole.header, whole.base.bytes, flags, segments);
  SrmHeader h3 = whole.header;
  h3.raw_planes = 3;
  const std::vector<uint8_t> three = write_srm(h3, whole.base.bytes, flags, segments);
  ASSERT_EQ(bytes.size(), three.size());
  size_t at = 0;
  while (at < bytes.size() && bytes[at] == three[at]) ++at;
  ASSERT_EQ(bytes[at], 2);
  for (int raw : {0, kSrmMaxPlane + 2, 255}) {
    std::vector<uint8_t> b = bytes;
    b[at] = static_cast<uint8_t>(raw);
    const uint64_t header_end = whole.header_size - 4;
    const uint32_t crc = crc32(b.data(), header_end);
    for (int i = 0; i < 4; ++i) b[header_end + i] = static_cast<uint8_t>(crc >> (8 * i));
    StatusOr<SrmFile> f = parse_srm(b.data(), b.size());
    ASSERT_FALSE(f.ok()) << raw;
    EXPECT_NE(f.status().message().find("raw planes"), std::string::npos) << f.status().message();
  }
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::vector<uint8_t>> noisy = segments;
    for (auto& s : noisy) {
      s.resize(trial % 2 ? s.size() : rng() % (2 * s.size() + 2));
      for (auto& x : s) x = static_cast<uint8_t>(rng());
    }
    (void)try_decode(write_srm(whole.header, whole.base.bytes, flags, noisy), trial % 3 - 1);
  }
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
  future[4] = kSrmVersion + 1;
  StatusOr<SrmFile> f = parse_srm(future.data(), future.size());
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(f.status().message().find("version " + std::to_string(kSrmVersion + 1)), std::string::npos)
      << f.status().message();
  future[4] = 0;
  f = parse_srm(future.data(), future.size());
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kUnsupported);
  std::vector<uint8_t> padded = golden();
  padded.push_back(0);
  f = parse_srm(padded.data(), padded.size());
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.status().message().find("after its last chunk"), std::string::npos) << f.status().message();
}

}  // namespace
}  // namespace srcodec
