// SHA-256 (FIPS 180-4) of files and byte strings, for the provenance a run record keeps: which
// input a mesh came from, and whether an output on disk is still the one that was written.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace hm {

class Sha256 {
 public:
  // With the x86 SHA extensions where the processor has them, unless `portable` (the plain C++
  // rounds, which the tests hold the instructions to).
  explicit Sha256(bool portable = false);
  void update(const void* data, std::size_t bytes);
  // The digest; the object must not be updated afterwards.
  std::array<std::uint8_t, 32> finish();
  bool uses_cpu_instructions() const;

 private:
  void blocks(const std::uint8_t* p, std::size_t count);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
  bool portable_ = false;
};

// Lower-case hex of the digest of `bytes`.
std::string sha256_hex(std::string_view bytes);
// Lower-case hex of the digest of a file's bytes. Throws IoError naming the file when it cannot be
// read.
std::string sha256_file(const std::string& path);

}  // namespace hm
