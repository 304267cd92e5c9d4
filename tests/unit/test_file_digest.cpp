// File fingerprints: FNV-1a 64 against the test vectors its authors publish (Noll's FNV test
// suite: "" -> cbf29ce484222325, "a" -> af63dc4c8601ec8c, "foobar" -> 85944171f73967e8), a file
// read in pieces hashing as one buffer, and a flipped bit or a dropped byte changing the digest.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "tfdem/file_digest.h"

namespace {

std::string scratch_file(const std::string &name, const std::string &content) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

TEST(FileDigest, PublishedFnv1aVectors) {
  EXPECT_EQ(tfdem::hex(tfdem::fnv1a("", 0)), "cbf29ce484222325");
  EXPECT_EQ(tfdem::hex(tfdem::fnv1a("a", 1)), "af63dc4c8601ec8c");
  EXPECT_EQ(tfdem::hex(tfdem::fnv1a("foobar", 6)), "85944171f73967e8");
}

TEST(FileDigest, HashContinuesOverPieces) {
  EXPECT_EQ(tfdem::fnv1a("bar", 3, tfdem::fnv1a("foo", 3)), tfdem::fnv1a("foobar", 6));
}

TEST(FileDigest, FileOfTwoMebibytesHashesAsOneBuffer) {
  std::string content(2 * (1 << 20) + 7, '\0');
  for (std::size_t i = 0; i < content.size(); ++i) content[i] = static_cast<char>(i * 131 % 251);
  const tfdem::FileDigest d = tfdem::digest_file(scratch_file("digest_big", content));
  EXPECT_EQ(d.size, content.size());
  EXPECT_EQ(d.hash, tfdem::fnv1a(content.data(), content.size()));
}

TEST(FileDigest, FlippedBitAndDroppedByteChangeIt) {
  const std::string content = "FoamFile { version 2.0; }\n// ***\n";
  const tfdem::FileDigest original = tfdem::digest_file(scratch_file("digest_a", content));
  std::string flipped = content;
  flipped[5] ^= 0x01;
  EXPECT_NE(tfdem::digest_file(scratch_file("digest_b", flipped)), original);
  EXPECT_NE(tfdem::digest_file(scratch_file("digest_c", content.substr(0, content.size() - 1))), original);
  EXPECT_EQ(tfdem::digest_file(scratch_file("digest_d", content)), original);
}

TEST(FileDigest, MissingFileNamesItAndTheReason) {
  try {
    tfdem::digest_file("/nonexistent/dem.restart");
    FAIL() << "no exception";
  } catch (const std::runtime_error &e) {
    EXPECT_NE(std::string(e.what()).find("'/nonexistent/dem.restart': No such file or directory"), std::string::npos)
        << e.what();
  }
}

TEST(FileDigest, HexRoundTripAndRefusal) {
  EXPECT_EQ(tfdem::from_hex("85944171f73967e8"), 0x85944171f73967e8ull);
  EXPECT_THROW(tfdem::from_hex("85944171f73967e"), std::invalid_argument);
  EXPECT_THROW(tfdem::from_hex("85944171f73967eZ"), std::invalid_argument);
}

}  // namespace
