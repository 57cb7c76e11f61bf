#include "cli/exit_status.hpp"

#include <CLI/Error.hpp>

#include "engine/base/errors.hpp"

#include "cli/output_file.hpp"

namespace kinema_cli {

int exit_status(const std::exception& error) {
  if (const auto* parse = dynamic_cast<const CLI::ParseError*>(&error)) {
    return parse->get_exit_code() == 0 ? status::success : status::bad_input;  // --help, --version
  }
  if (dynamic_cast<const OutputError*>(&error)) return status::output;
  if (dynamic_cast<const kinema::SingularPositionError*>(&error)) return status::singular;
  if (dynamic_cast<const kinema::AssemblyError*>(&error)) return status::unassembled;
  if (dynamic_cast<const kinema::InputError*>(&error)) return status::bad_input;  // UnitError too
  return status::internal;
}

}  // namespace kinema_cli
