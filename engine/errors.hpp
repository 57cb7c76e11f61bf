// One exception hierarchy for kinema; the command-line tool turns the kind
// into its exit status, so scripts can tell bad input from an unassemblable
// position.
#pragma once

#include <stdexcept>
#include <string>

namespace kinema {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  /// Exit status the command-line tool uses for this kind of error.
  virtual int exit_status() const { return 1; }
};

/// The mechanism file is wrong: syntax, names, units, counts, values.
class InputError : public Error {
 public:
  using Error::Error;
  int exit_status() const override { return 2; }
};

/// A unit that is not understood or does not fit where it is used.
class UnitError : public InputError {
 public:
  using InputError::InputError;
};

/// The loops cannot be closed at the requested input value.
class AssemblyError : public Error {
 public:
  using Error::Error;
  int exit_status() const override { return 3; }
};

/// Phi_q is rank-deficient (toggle / dead centre): rates are undefined there.
class SingularPositionError : public Error {
 public:
  using Error::Error;
  int exit_status() const override { return 4; }
};

}  // namespace kinema
