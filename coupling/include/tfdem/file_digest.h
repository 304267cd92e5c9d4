// Fingerprints of files, for checkpoints that must be resumed only as they were written: a
// file's size and its FNV-1a 64-bit hash (Fowler, Noll, Vo; the published offset basis and
// prime). Not cryptographic: it catches truncation, bit flips and stray writes, not tampering.
#ifndef TFDEM_FILE_DIGEST_H
#define TFDEM_FILE_DIGEST_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace tfdem {

struct FileDigest {
  std::uint64_t size = 0;  // bytes
  std::uint64_t hash = 0;  // FNV-1a 64 of the whole content

  bool operator==(const FileDigest &other) const { return size == other.size && hash == other.hash; }
  bool operator!=(const FileDigest &other) const { return !(*this == other); }
};

// FNV-1a 64 continued over `count` bytes from `hash` (start from kFnv1aOffsetBasis).
constexpr std::uint64_t kFnv1aOffsetBasis = 14695981039346656037ull;
std::uint64_t fnv1a(const void *bytes, std::size_t count, std::uint64_t hash = kFnv1aOffsetBasis);

// Size and hash of a file's content; throws std::runtime_error naming the file and the
// system's reason when it cannot be read to the end.
FileDigest digest_file(const std::string &path);

// The hash as 16 lower-case hex digits, and back (std::invalid_argument for anything else).
std::string hex(std::uint64_t hash);
std::uint64_t from_hex(const std::string &text);

}  // namespace tfdem

#endif
