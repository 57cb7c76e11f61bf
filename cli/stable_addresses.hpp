// Same input, same output, byte for byte. GiNaC orders the terms of sums and
// products by hash values that include the addresses of type information, so with
// address-space randomisation a formula printed its terms in another order in each
// run (issue 9, finding 17; the numbers do not depend on it: the tape orders
// operands itself). The command-line tool therefore runs with randomisation off —
// or, as the default build links it (CMakeLists.txt, KINEMA_STATIC_CLI), with GiNaC
// linked into a position-dependent program, where those addresses are fixed at link
// time and no second exec is needed.
#pragma once

namespace kinema_cli {

/// Re-executes the program with address randomisation off (Linux personality
/// ADDR_NO_RANDOMIZE), once; returns (and the run goes on as it is) where that is
/// not possible.
void run_with_stable_addresses(char** argv);

}  // namespace kinema_cli
