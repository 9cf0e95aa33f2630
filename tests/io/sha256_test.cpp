#include "io/sha256.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "core/error.h"

namespace hm {
namespace {

// FIPS 180-4 example vectors, and lengths around the 55/56/64-byte padding boundaries.
TEST(Sha256, KnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1'000'000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// The x86 SHA extensions (where the processor has them) against the plain C++ rounds: the same
// digest for every length around the block boundaries and every way of cutting the input into
// updates (a part block buffered, whole blocks taken straight from the input).
TEST(Sha256, CpuInstructionsAndPortableRoundsAgree) {
  std::mt19937 rng(5);
  std::string data(300'000, '\0');
  for (char& c : data) c = static_cast<char>(rng());
  for (std::size_t n : {0, 1, 55, 56, 63, 64, 65, 127, 128, 129, 1000, 65'536, 300'000}) {
    for (std::size_t chunk : {1, 7, 64, 100, 4096, 1 << 20}) {
      if (chunk == 1 && n > 1000) continue;
      Sha256 fast, plain(true);
      for (std::size_t at = 0; at < n; at += chunk) {
        const std::size_t take = std::min(chunk, n - at);
        fast.update(data.data() + at, take);
        plain.update(data.data() + at, take);
      }
      EXPECT_EQ(fast.finish(), plain.finish()) << n << " bytes in updates of " << chunk;
    }
  }
  EXPECT_FALSE(Sha256(true).uses_cpu_instructions());
  std::printf("Sha256: %s\n",
              Sha256().uses_cpu_instructions() ? "x86 SHA extensions" : "plain C++");
}

TEST(Sha256, FileMatchesBytesAndMissingFileNamesIt) {
  const auto path = std::filesystem::temp_directory_path() / "hm_sha256_test.bin";
  std::string bytes;
  for (int i = 0; i < 200'000; ++i) bytes += static_cast<char>(i * 7 + 3);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(sha256_file(path.string()), sha256_hex(bytes));
  for (std::size_t n : {55, 56, 63, 64, 65}) {
    EXPECT_NE(sha256_hex(bytes.substr(0, n)), sha256_hex(bytes.substr(0, n + 1)));
  }
  try {
    sha256_file("/nonexistent/hull.igs");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/hull.igs"), std::string::npos);
  }
}

}  // namespace
}  // namespace hm
