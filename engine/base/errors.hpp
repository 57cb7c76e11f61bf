// One exception hierarchy for kinema. The kind says what went wrong; the
// command-line tool decides the exit status from it (cli/exit_status.hpp), so
// scripts can tell bad input from an unassemblable position.
#pragma once

#include <string>

#include "engine/base/error.hpp"  // kinema::Error, the base (also the facade's <kinema/error.hpp>)

namespace kinema {

/// The mechanism file is wrong: syntax, names, units, counts, values.
class InputError : public Error {
 public:
  using Error::Error;
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
};

/// A run stopped because its caller asked it to (StudyOptions::cancelled).
class Cancelled : public Error {
 public:
  using Error::Error;
};

/// Phi_q is rank-deficient (toggle / dead centre): rates are undefined there.
class SingularPositionError : public Error {
 public:
  using Error::Error;
};

}  // namespace kinema
