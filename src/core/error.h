// The typed error hierarchy. Stages throw these; only cli/ catches them and maps them to exit
// codes. Nothing else catches, so an error is never swallowed halfway up the pipeline.
#pragma once

#include <stdexcept>
#include <string>

namespace hm {

// Process exit codes, documented in the README ("Reliability").
enum class ExitCode : int {
  kOk = 0,
  kInternal = 1,     // a bug in hullmesh: please report
  kUsage = 2,        // bad command line or option value
  kBadInput = 3,     // the input file is malformed or not what it claims to be
  kLimit = 4,        // the input exceeds a configured resource limit
  kGeometry = 5,     // the geometry cannot be processed (degenerate, impossible request)
  kIo = 6,           // a file cannot be read or written
  kQualityGate = 7,  // the result fails a requested quality gate
};

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual ExitCode exit_code() const { return ExitCode::kInternal; }
};

class UsageError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kUsage; }
};

// Malformed input: the message names the file, the entity (DE number) or line, and the fault.
class InputError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kBadInput; }
};

// IGES-specific malformed input.
class IgesError : public InputError {
 public:
  using InputError::InputError;
};

// A declared size or count exceeds a resource limit; raised before anything is allocated.
class LimitError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kLimit; }
};

class GeometryError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kGeometry; }
};

class IoError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kIo; }
};

class InternalError : public Error {
 public:
  using Error::Error;
};

}  // namespace hm
