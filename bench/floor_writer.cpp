// The floor under `kinema eval ... -o FILE` on this machine (issue 10's 300x target):
// a program linked with GiNaC and CLN exactly as the kinema program is, that computes
// nothing and writes BYTES bytes of text into a new FILE in 1 MB pieces. The time it
// takes is what start-up with the mandated libraries plus writing the output costs
// before any reading, deriving, solving or formatting.
// usage: kinema_floor_writer BYTES FILE
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ginac/ginac.h>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: kinema_floor_writer BYTES FILE\n");
    return 2;
  }
  // One expression, so that GiNaC's and CLN's objects (and their static set-up) are
  // linked in as in kinema: a program that never names GiNaC would leave them out.
  const GiNaC::symbol x("x");
  if (GiNaC::diff(GiNaC::sin(x), x).nops() != 1) return 1;
  const long long bytes = std::atoll(argv[1]);
  const int out = ::open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (bytes < 0 || out < 0) return 1;
  std::vector<char> piece(1 << 20);
  for (long long done = 0; done < bytes;) {
    const std::size_t n = static_cast<std::size_t>(std::min<long long>(bytes - done, static_cast<long long>(piece.size())));
    std::memset(piece.data(), '7', n);  // the text is written afresh, as a program's output is
    if (::write(out, piece.data(), n) != static_cast<ssize_t>(n)) return 1;
    done += static_cast<long long>(n);
  }
  return ::close(out) == 0 ? 0 : 1;
}
