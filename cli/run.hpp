// The kinema command without its main: tests run it in the same process where the
// program's start-up is not what they test (and see what it solved).
#pragma once

namespace kinema_cli {

/// Parses the arguments and runs the subcommand; returns the exit status. Throws
/// kinema::Error for what the user gave (main words it and maps it to a status).
int run(int argc, char** argv);

}  // namespace kinema_cli
