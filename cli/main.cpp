// kinema command-line tool: a thin layer over the library (engine/, readers/ and the front ends). main
// fixes the addresses GiNaC hashes (so outputs are the same bytes in every run), runs
// the command (cli/run.cpp) and turns what it throws into a message and an exit status.
#include <iostream>
#include <new>

#include "engine/base/errors.hpp"
#include "engine/base/user_text.hpp"

#include "cli/exit_status.hpp"
#include "cli/output_file.hpp"
#include "cli/run.hpp"
#include "cli/stable_addresses.hpp"

int main(int argc, char** argv) {
  kinema_cli::run_with_stable_addresses(argv);
  try {
    const int status = kinema_cli::run(argc, argv);
    kinema_cli::flush_standard_output();  // help or version on a full disk is an error too
    return status;
  } catch (const kinema::Error& error) {
    std::cerr << "kinema: error: " << kinema::terminal_text(error.what()) << "\n";
    return kinema_cli::exit_status(error);
  } catch (const std::bad_alloc&) {
    std::cerr << "kinema: error: out of memory; evaluate fewer values per run (a coarser --sweep, or split it)\n";
    return kinema_cli::status::internal;
  } catch (const std::exception& error) {
    std::cerr << "kinema: internal error: " << kinema::terminal_text(error.what()) << "\n";
    return kinema_cli::exit_status(error);
  } catch (...) {
    std::cerr << "kinema: internal error: unknown exception\n";
    return kinema_cli::status::internal;
  }
}
