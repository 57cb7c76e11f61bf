// Using kinema as a library: load a mechanism, solve a few crank angles,
// read the rates. Built and run by ctest against an installed kinema
// (find_package(kinema)), so this example stays true.
#include <cstdio>

#include <kinema/engine/model.hpp>
#include <kinema/engine/report/diagnostics.hpp>

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "samples/four_bar.toml";
  try {
    const auto model = kinema::load_model(path);
    // Input values in SI (rad); the rates default to the file's.
    const kinema::MotionTable table = kinema::analyse(model, {0.1, 0.2, 0.3});
    for (const kinema::MotionState& state : table) {
      if (state.status != kinema::Status::ok) {
        std::fprintf(stderr, "%s\n", kinema::describe_failure(model.system, state).c_str());
        return 1;
      }
      // Unknowns in file order: theta3, theta4 for the four-bar.
      std::printf("theta2 = %.3f rad: omega3 = %.6f rad/s, alpha3 = %.6f rad/s^2\n", state.input, state.qd[0],
                  state.qdd[0]);
    }
    // One value at a time, each from the last (a controller, a simulation step).
    kinema::Workspace workspace(model);
    kinema::MotionState state = table[table.size() - 1];
    const auto& input = model.system.input;
    if (!workspace.advance(0.31, input.rate_value, input.second_rate_value, state)) {
      std::fprintf(stderr, "the branch does not reach 0.31 rad\n");
      return 1;
    }
    std::printf("theta2 = %.3f rad: omega3 = %.6f rad/s (advanced from the last value)\n", state.input, state.qd[0]);
  } catch (const kinema::Error& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
