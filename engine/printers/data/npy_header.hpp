// The header of a NumPy .npy file holding a structured array, written once for every
// table kinema writes as npy (a sweep's results, a design study's designs).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace kinema {

/// A field of a structured array: its name and its numpy type ("<f8", "|u1", "|b1", ...).
struct NpyField {
  std::string name;
  std::string type;
};

/// The magic, version (1.0, or 2.0 when the dict does not fit 1.0's 16-bit length), length and
/// the dict literal of a one-dimensional array of `rows` records with `fields`, padded with
/// spaces and a newline so that the data that follows starts on a 64-byte boundary.
std::string npy_header(const std::vector<NpyField>& fields, std::size_t rows);

}  // namespace kinema
