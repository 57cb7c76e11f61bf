// What kinema throws, for a library user and for kinema's own code alike: one class,
// whose message says what is wrong and where (file:line), as the command line prints
// it. The engine's kinds of error (engine/base/errors.hpp: bad input, units, assembly)
// derive from it, so a program catches kinema::Error alone and needs nothing else.
#pragma once

#include <stdexcept>

namespace kinema {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace kinema
