#include "tfdem/file_digest.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace tfdem {

std::uint64_t fnv1a(const void *bytes, std::size_t count, std::uint64_t hash) {
  constexpr std::uint64_t kPrime = 1099511628211ull;  // 2^40 + 2^8 + 0xb3
  const auto *b = static_cast<const unsigned char *>(bytes);
  for (std::size_t i = 0; i < count; ++i) {
    hash ^= b[i];
    hash *= kPrime;
  }
  return hash;
}

FileDigest digest_file(const std::string &path) {
  std::FILE *in = std::fopen(path.c_str(), "rb");
  if (!in) throw std::runtime_error("cannot read '" + path + "': " + std::strerror(errno));
  FileDigest d;
  d.hash = kFnv1aOffsetBasis;
  std::vector<char> buffer(1 << 20);
  std::size_t got;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), in)) > 0) {
    d.hash = fnv1a(buffer.data(), got, d.hash);
    d.size += got;
  }
  const bool failed = std::ferror(in);
  const int error = errno;
  std::fclose(in);
  if (failed) throw std::runtime_error("cannot read '" + path + "' to its end: " + std::strerror(error));
  return d;
}

std::string hex(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::uint64_t from_hex(const std::string &text) {
  if (text.size() != 16 || text.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw std::invalid_argument("'" + text + "' is not a hash of 16 hex digits");
  return std::stoull(text, nullptr, 16);
}

}  // namespace tfdem
