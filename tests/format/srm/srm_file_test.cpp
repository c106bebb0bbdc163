#include "format/srm/srm_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <vector>

#include "format/checksum.h"

namespace srcodec {
namespace {

struct Sample {
  SrmHeader header;
  std::vector<uint8_t> base;
  std::vector<std::vector<uint8_t>> flags, segments;
  std::vector<uint8_t> file;
};

std::vector<uint8_t> filled(size_t n, uint8_t seed) {
  std::vector<uint8_t> b(n);
  for (size_t i = 0; i < n; ++i) b[i] = static_cast<uint8_t>(seed + 7 * i);
  return b;
}

// Two levels, three planes: 9 segments, one of them empty.
Sample make_sample() {
  Sample s;
  SrmHeader& h = s.header;
  h.input_vertices = 1234;
  h.input_triangles = 2400;
  h.bbox_min = {-1, -2, -3};
  h.bbox_max = {1, 2, 3.5};
  h.levels = 2;
  h.base_bits = 10;
  h.grid_step = 6.5 / 1023;
  h.base_vertices = 12;
  h.base_triangles = 20;
  h.level_vertices = {12, 30, 120};
  h.quant_step = 1e-4;
  h.tangential_factor = 4.0;
  h.top_plane = 2;
  s.base = filled(40, 1);
  s.flags = {filled(3, 2), filled(5, 3)};
  for (int i = 0; i < 9; ++i) s.segments.push_back(filled(i == 4 ? 0 : 10 + i, static_cast<uint8_t>(i)));
  s.file = write_srm(h, s.base, s.flags, s.segments);
  return s;
}

TEST(SrmFile, RoundTripsHeaderAndChunks) {
  const Sample s = make_sample();
  StatusOr<SrmFile> f = parse_srm(s.file.data(), s.file.size());
  ASSERT_TRUE(f.ok()) << f.status().message();
  const SrmHeader& h = f->header;
  EXPECT_EQ(h.input_vertices, 1234u);
  EXPECT_EQ(h.bbox_max.z(), 3.5);
  EXPECT_EQ(h.levels, 2);
  EXPECT_EQ(h.level_vertices, s.header.level_vertices);
  EXPECT_EQ(h.tangential_factor, 4.0);
  EXPECT_EQ(h.scale(2, 0), 1.0);
  EXPECT_EQ(h.scale(1, 1), 2.0);
  EXPECT_EQ(h.scale(0, 1), 0.25);
  EXPECT_EQ(h.top_plane, 2);
  EXPECT_EQ(f->declared_size, s.file.size());
  EXPECT_EQ(f->base.bytes, s.base);
  ASSERT_EQ(f->flags.size(), 2u);
  EXPECT_EQ(f->flags[1].bytes, s.flags[1]);
  ASSERT_EQ(f->segments.size(), 9u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(f->segments[i].bytes, s.segments[i]) << i;
    EXPECT_TRUE(verify_chunk(f->segments[i], true, "segment").ok());
  }
  EXPECT_EQ(h.segment_index(0, 2), 8u);
  EXPECT_TRUE(verify_chunk(f->base, false, "base").ok());
}

TEST(SrmFile, EveryPrefixPastTheHeaderParsesAndShorterOnesSayWhy) {
  const Sample s = make_sample();
  const size_t header = parse_srm(s.file.data(), s.file.size())->header_size;
  for (size_t n = 0; n <= s.file.size(); ++n) {
    StatusOr<SrmFile> f = parse_srm(s.file.data(), n);
    if (n < header) {
      ASSERT_FALSE(f.ok()) << n;
      EXPECT_NE(f.status().message().find("byte"), std::string::npos) << f.status().message();
      continue;
    }
    ASSERT_TRUE(f.ok()) << n << ": " << f.status().message();
    size_t present = f->base.bytes.size();
    for (const auto& c : f->flags) present += c.bytes.size();
    for (const auto& c : f->segments) {
      present += c.bytes.size();
      EXPECT_LE(c.bytes.size(), c.declared);
    }
    EXPECT_EQ(present + header, n);
  }
}

TEST(SrmFile, MaxBytesActsAsACut) {
  const Sample s = make_sample();
  SrmReadOptions o;
  o.max_bytes = s.file.size() - 5;
  StatusOr<SrmFile> f = parse_srm(s.file.data(), s.file.size(), o);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->file_size, s.file.size() - 5);
  EXPECT_FALSE(f->segments.back().complete());
  EXPECT_EQ(f->segments.back().bytes.size(), s.segments.back().size() - 5);
}

TEST(SrmFile, LowLevelsLoadOnlyTheirChunks) {
  const Sample s = make_sample();
  SrmReadOptions o;
  o.max_level = 1;
  StatusOr<SrmFile> f = parse_srm(s.file.data(), s.file.size(), o);
  ASSERT_TRUE(f.ok());
  EXPECT_TRUE(f->flags[0].loaded);
  EXPECT_FALSE(f->flags[1].loaded);
  for (size_t i = 0; i < f->segments.size(); ++i) EXPECT_EQ(f->segments[i].loaded, i % 3 <= 1) << i;
}

TEST(SrmFile, ReadsFromDiskLikeFromMemory) {
  const Sample s = make_sample();
  const std::string path = ::testing::TempDir() + "/sample.srm";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(s.file.data()),
                                              static_cast<std::streamsize>(s.file.size()));
  SrmReadOptions o;
  o.max_level = 1;
  o.max_bytes = s.file.size() - 3;
  StatusOr<SrmFile> disk = read_srm(path, o);
  StatusOr<SrmFile> memory = parse_srm(s.file.data(), s.file.size(), o);
  ASSERT_TRUE(disk.ok()) << disk.status().message();
  ASSERT_TRUE(memory.ok());
  EXPECT_EQ(disk->base.bytes, memory->base.bytes);
  for (size_t i = 0; i < memory->segments.size(); ++i) {
    EXPECT_EQ(disk->segments[i].loaded, memory->segments[i].loaded);
    EXPECT_EQ(disk->segments[i].bytes, memory->segments[i].bytes) << i;
  }
  EXPECT_FALSE(read_srm(path + ".missing").ok());
}

TEST(SrmFile, CorruptionIsCaught) {
  const Sample s = make_sample();
  const size_t header = parse_srm(s.file.data(), s.file.size())->header_size;
  std::vector<uint8_t> bad = s.file;
  bad[header / 2] ^= 0x10;
  StatusOr<SrmFile> f = parse_srm(bad.data(), bad.size());
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.status().message().find("checksum"), std::string::npos) << f.status().message();

  bad = s.file;
  bad[header + 3] ^= 0x01;  // inside the base chunk
  f = parse_srm(bad.data(), bad.size());
  ASSERT_TRUE(f.ok());
  Status v = verify_chunk(f->base, false, "the base mesh");
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.message().find("the base mesh (bytes"), std::string::npos) << v.message();

  bad = s.file;
  bad[0] = 'X';
  EXPECT_NE(parse_srm(bad.data(), bad.size()).status().message().find("not an .srm"), std::string::npos);
  bad = s.file;
  bad[4] = 9;
  EXPECT_EQ(parse_srm(bad.data(), bad.size()).status().code(), StatusCode::kUnsupported);
}

TEST(SrmFile, GarbageNeverCrashes) {
  std::mt19937 rng(7);
  const Sample s = make_sample();
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> b = s.file;
    if (trial % 2) {
      b.resize(rng() % 200);
      for (auto& x : b) x = static_cast<uint8_t>(rng());
      if (b.size() >= 5) b[0] = 0x89, b[1] = 'S', b[2] = 'R', b[3] = 'M', b[4] = 1;
    } else {
      for (int k = 0; k < 3; ++k) b[rng() % b.size()] = static_cast<uint8_t>(rng());
    }
    (void)parse_srm(b.data(), b.size());
  }
  SUCCEED();
}

TEST(SrmFile, TruncationKeepsWholeSegmentsThenCutsOneAndListsOnlyThose) {
  const Sample s = make_sample();
  size_t total = 0;
  for (const auto& seg : s.segments) total += seg.size();
  for (uint64_t keep : {uint64_t{0}, uint64_t{10}, uint64_t{15}, uint64_t{47}, uint64_t{total}}) {
    StatusOr<std::vector<uint8_t>> cut = truncate_srm(s.file, keep);
    ASSERT_TRUE(cut.ok()) << cut.status().message();
    StatusOr<SrmFile> f = parse_srm(cut->data(), cut->size());
    ASSERT_TRUE(f.ok()) << f.status().message();
    EXPECT_EQ(f->declared_size, cut->size());
    EXPECT_EQ(f->base.bytes, s.base);
    uint64_t kept = 0;
    for (size_t i = 0; i < f->segments.size(); ++i) {
      const auto& c = f->segments[i];
      EXPECT_TRUE(c.complete());
      EXPECT_TRUE(verify_chunk(c, true, "segment").ok());
      // Each kept segment is the original's start.
      EXPECT_TRUE(std::equal(c.bytes.begin(), c.bytes.end(), s.segments[i].begin())) << i;
      kept += c.bytes.size();
    }
    EXPECT_EQ(kept, keep);
    if (keep < total) {
      EXPECT_LT(cut->size(), s.file.size());
    }
  }
  EXPECT_EQ(truncate_srm(s.file, total).value(), s.file);
  std::vector<uint8_t> prefix(s.file.begin(), s.file.end() - 4);
  EXPECT_TRUE(truncate_srm(prefix, 5).ok());
}

// Version 3: the crease chunk sits between the base mesh and the flags, with
// its entry after the base mesh's; the raw plane count may be 0. Without
// creases the same header writes version 1 or 2, as it always did.
TEST(SrmFile, Version3CarriesTheCreaseChunkRightAfterTheBaseMesh) {
  const Sample s = make_sample();
  ASSERT_EQ(s.file[4], 1);
  const std::vector<uint8_t> creases = filled(6, 9);
  for (int raw : {0, 2}) {
    SrmHeader h = s.header;
    h.raw_planes = raw;
    const std::vector<uint8_t> without = write_srm(h, s.base, s.flags, s.segments);
    EXPECT_EQ(without[4], raw > 0 ? 2 : 1);
    const std::vector<uint8_t> file = write_srm(h, s.base, s.flags, s.segments, creases);
    ASSERT_EQ(file[4], 3);
    // The table grows by the entry (a 1-byte length and a CRC-32), the file by the chunk too.
    const uint64_t entry = 1 + 4 + (raw > 0 ? 0 : 1);  // version 1 has no raw plane byte
    EXPECT_EQ(file.size(), without.size() + entry + creases.size()) << raw;
    StatusOr<SrmFile> f = parse_srm(file.data(), file.size());
    ASSERT_TRUE(f.ok()) << f.status().message();
    EXPECT_TRUE(f->header.has_creases);
    EXPECT_EQ(f->header.version(), 3);
    EXPECT_EQ(f->header.raw_planes, raw);
    EXPECT_EQ(f->creases.offset, f->base.offset + s.base.size());
    EXPECT_EQ(f->flags[0].offset, f->creases.offset + creases.size());
    EXPECT_EQ(f->creases.bytes, creases);
    EXPECT_TRUE(verify_chunk(f->creases, false, "the creases").ok());
    EXPECT_EQ(f->flags[1].bytes, s.flags[1]);
    EXPECT_EQ(f->segments.back().bytes, s.segments.back());
    // Every level needs the creases, level 0 too.
    SrmReadOptions o;
    o.max_level = 0;
    EXPECT_TRUE(parse_srm(file.data(), file.size(), o)->creases.loaded);
    // A cut inside the crease chunk: the part present, not complete.
    StatusOr<SrmFile> cut = parse_srm(file.data(), f->creases.offset + 2);
    ASSERT_TRUE(cut.ok()) << cut.status().message();
    EXPECT_EQ(cut->creases.bytes.size(), 2u);
    EXPECT_FALSE(cut->creases.complete());
    // A damaged crease chunk fails its checksum, named.
    std::vector<uint8_t> bad = file;
    bad[f->creases.offset + 1] ^= 0x10;
    const Status status = verify_chunk(parse_srm(bad.data(), bad.size())->creases, false, "the creases");
    EXPECT_NE(status.message().find("the creases (bytes"), std::string::npos) << status.message();
    // Truncation keeps the creases and version 3.
    const std::vector<uint8_t> small = truncate_srm(file, 12).value();
    EXPECT_EQ(small[4], 3);
    EXPECT_EQ(parse_srm(small.data(), small.size())->creases.bytes, creases);
    EXPECT_FALSE(truncate_srm(file.data(), f->creases.offset + 2, 0).ok());
  }
}

TEST(SrmFile, Version2NeedsRawPlanesVersion3DoesNot) {
  const Sample s = make_sample();
  for (bool with_creases : {false, true}) {
    const std::vector<uint8_t> creases = with_creases ? filled(3, 1) : std::vector<uint8_t>{};
    SrmHeader h = s.header;
    h.raw_planes = 1;
    std::vector<uint8_t> file = write_srm(h, s.base, s.flags, s.segments, creases);
    h.raw_planes = 3;
    const std::vector<uint8_t> three = write_srm(h, s.base, s.flags, s.segments, creases);
    size_t at = 0;  // the raw plane count: the first byte the two differ in
    while (file[at] == three[at]) ++at;
    ASSERT_EQ(file[at], 1);
    file[at] = 0;
    const size_t header = parse_srm(three.data(), three.size())->header_size;
    const uint32_t crc = crc32(file.data(), header - 4);
    for (int i = 0; i < 4; ++i) file[header - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
    StatusOr<SrmFile> f = parse_srm(file.data(), file.size());
    ASSERT_EQ(f.ok(), with_creases) << (f.ok() ? "" : f.status().message());
    if (with_creases) {
      EXPECT_EQ(f->header.raw_planes, 0);
    } else {
      EXPECT_NE(f.status().message().find("raw planes"), std::string::npos) << f.status().message();
    }
  }
}

TEST(Checksum, MatchesTheStandardCheckValue) {
  const uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc32(digits, 9), 0xCBF43926u);
}

// The eight-bytes-at-a-time path against the definition, bit by bit, at every
// length and alignment around the 8-byte steps, and continued from a prefix.
TEST(Checksum, EqualsTheBitwiseDefinition) {
  const auto bitwise = [](const uint8_t* data, size_t size) {
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < size; ++i) {
      c ^= data[i];
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return ~c;
  };
  std::vector<uint8_t> bytes(100);
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(i * 37 + (i >> 3) * 11 + 5);
  for (size_t from = 0; from < 9; ++from)
    for (size_t size = 0; from + size <= bytes.size(); ++size) {
      const uint8_t* p = bytes.data() + from;
      ASSERT_EQ(crc32(p, size), bitwise(p, size)) << from << " " << size;
      const size_t half = size / 2;
      ASSERT_EQ(crc32(p + half, size - half, crc32(p, half)), bitwise(p, size)) << from << " " << size;
    }
}

}  // namespace
}  // namespace srcodec
