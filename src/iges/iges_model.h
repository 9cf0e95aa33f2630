// The parsed file: header, directory and the tokenized parameters of every entity, with typed
// access that reports malformed fields as EntityFault (one entity skipped, not the file).
#pragma once

#include <cstdint>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "core/limits.h"
#include "core/vec.h"
#include "iges/iges_directory.h"
#include "iges/iges_records.h"
#include "iges/read_iges.h"

namespace hm::iges {

// A malformed entity: converters throw it, the driver turns it into a Diagnostic and skips the
// entity that needed it. `index` is the directory index of the entity at fault.
class EntityFault : public std::exception {
 public:
  EntityFault(int index, std::string message) : index_(index), message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }
  int index() const { return index_; }

 private:
  int index_;
  std::string message_;
};

struct IgesModel {
  std::string source;
  IgesHeader header;
  Delimiters delims;
  ResourceLimits limits;
  std::vector<DirEntry> entries;           // index i holds DE number 2i+1
  std::string pdata;                       // P section, columns 1..64, 64 characters per line
  std::vector<Token> tokens;               // every entity's parameters, type number first
  std::vector<std::uint32_t> first_token;  // entries.size() + 1 offsets into tokens
  std::vector<std::string> token_error;    // per entity; empty when tokenized cleanly
  Diagnostics file_diagnostics;            // section-count and header warnings

  std::size_t size() const { return entries.size(); }
  // Directory index of a DE pointer, or -1 when it does not name an entry.
  int index_of(std::int64_t de) const {
    if (de < 1 || de % 2 == 0 || (de - 1) / 2 >= static_cast<std::int64_t>(entries.size())) {
      return -1;
    }
    return static_cast<int>((de - 1) / 2);
  }
};

// Splits, parses the header and directory and tokenizes every entity. Throws IgesError for
// structural breakage and LimitError when the entity count or a parameter count is over the
// limits.
IgesModel load_model(std::string_view text, const std::string& source,
                     const ResourceLimits& limits);

// Typed access to one entity's parameters. Parameter k is the k-th field after the type number
// (1-based, as the IGES specification counts them).
class Params {
 public:
  Params(const IgesModel& m, int index);

  int index() const { return index_; }
  const DirEntry& entry() const { return m_->entries[static_cast<std::size_t>(index_)]; }
  // Number of parameters after the type number.
  std::size_t size() const { return count_; }
  bool has(std::size_t k) const { return k >= 1 && k <= count_ && !tok(k).empty(); }

  double real(std::size_t k) const;
  double real_or(std::size_t k, double fallback) const;
  std::int64_t integer(std::size_t k) const;
  std::int64_t integer_or(std::size_t k, std::int64_t fallback) const;
  // An integer in [lo, hi]; faults with `what` naming the field otherwise.
  int bounded(std::size_t k, std::int64_t lo, std::int64_t hi, const char* what) const;
  std::string text(std::size_t k) const;
  // A DE pointer: directory index, or -1 for a null (0 or blank) pointer. Faults when the pointer
  // names no entry (dangling).
  int pointer(std::size_t k) const;
  // Same, but the entity must have one of the given types.
  int pointer_to(std::size_t k, std::initializer_list<int> types, const char* what) const;
  // Faults unless parameters 1..k exist.
  void require(std::uint64_t k, const char* what) const;

  [[noreturn]] void fault(const std::string& message) const;

 private:
  const Token& tok(std::size_t k) const { return m_->tokens[first_ + k]; }
  const IgesModel* m_;
  int index_;
  std::size_t first_ = 0;
  std::size_t count_ = 0;
};

// Reads `count` knots from parameter k on; faults when they decrease or span nothing.
std::vector<double> read_knots(const Params& p, std::size_t k, std::size_t count, const char* name);
// Reads `count` weights from parameter k on; faults unless each is positive.
std::vector<double> read_weights(const Params& p, std::size_t k, std::size_t count);
// Reads `count` points (x, y, z triples) from parameter k on.
std::vector<Vec3d> read_points(const Params& p, std::size_t k, std::size_t count);

// "DE 37 (type 128)".
std::string describe(const IgesModel& m, int index);

}  // namespace hm::iges
