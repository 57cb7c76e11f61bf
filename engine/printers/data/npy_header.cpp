#include "engine/printers/data/npy_header.hpp"

#include <cstdint>

namespace kinema {

std::string npy_header(const std::vector<NpyField>& fields, std::size_t rows) {
  std::string descr = "[";
  for (std::size_t k = 0; k < fields.size(); ++k)
    descr += (k ? ", ('" : "('") + fields[k].name + "', '" + fields[k].type + "')";
  descr += "]";
  std::string dict = "{'descr': " + descr + ", 'fortran_order': False, 'shape': (" + std::to_string(rows) + ",), }";
  const bool version1 = dict.size() + 12 < 65000;
  const std::size_t prefix = version1 ? 10 : 12;  // magic 6 + version 2 + length 2 or 4
  const std::size_t total = (prefix + dict.size() + 1 + 63) / 64 * 64;
  dict += std::string(total - prefix - dict.size() - 1, ' ') + "\n";
  std::string header = "\x93NUMPY";
  header += version1 ? '\x01' : '\x02';
  header += '\x00';
  const auto length = static_cast<std::uint32_t>(dict.size());
  for (std::size_t b = 0; b < (version1 ? 2u : 4u); ++b) header += static_cast<char>((length >> (8 * b)) & 0xff);
  return header + dict;
}

}  // namespace kinema
