#include "cli/stable_addresses.hpp"

#if defined(__linux__)
#include <sys/personality.h>
#include <unistd.h>
#endif

namespace kinema_cli {

void run_with_stable_addresses(char** argv) {
#if defined(KINEMA_ADDRESSES_FIXED_AT_LINK)
  (void)argv;  // GiNaC linked into a position-dependent program: nothing to turn off
#elif defined(__linux__)
  const int current = personality(0xffffffff);
  if (current == -1 || (current & ADDR_NO_RANDOMIZE) != 0) return;  // unknown, or already off
  if (personality(static_cast<unsigned long>(current) | ADDR_NO_RANDOMIZE) == -1) return;
  execv("/proc/self/exe", argv);  // returns only on failure: then go on as we are
  personality(static_cast<unsigned long>(current));
#else
  (void)argv;
#endif
}

}  // namespace kinema_cli
