// The structure of a joints-and-links mechanism in words, once for every printer:
// Grübler's count and the solving order (driver, dyads, links that form no dyad).
#pragma once

#include <string>
#include <vector>

#include "loops/mechanism.hpp"

namespace kinema {

/// "3(n - 1) - 2j = 3*5 - 2*7 = 1 (n = 6 bodies with ground, j = 7 joints)".
std::string mobility_text(const Linkage& linkage);

/// One line per step: "driver: link 1 (A)", "dyad 1, RRR: links 2, 3; joints B, C, D",
/// "not a dyad: links 5, 6, 7, solved together by Newton on their loops".
std::vector<std::string> structure_lines(const Linkage& linkage);

/// "dyad 1 (RRR: links 2, 3; joints B, C, D)": the k-th dyad in solving order.
std::string describe_dyad(const Linkage& linkage, std::size_t k);

}  // namespace kinema
