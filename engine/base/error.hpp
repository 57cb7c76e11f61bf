// What kinema throws, for a library user and for kinema's own code alike: one class,
// whose message says what is wrong and where (file:line), as the command line prints
// it. The engine's kinds of error (engine/base/errors.hpp: bad input, units, assembly)
// derive from it, so a program catches kinema::Error alone and needs nothing else.
// It belongs to the lowest stage; the facade gives it to programs as <kinema/error.hpp>
// (the build copies this file there and installs it with the facade's headers), so it
// includes nothing but the standard library. A named guard, not #pragma once: the file and
// its copy are one header to the compiler.
#ifndef KINEMA_ERROR_HPP
#define KINEMA_ERROR_HPP

#include <stdexcept>

namespace kinema {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace kinema

#endif  // KINEMA_ERROR_HPP
