// Using kinema as a library: load a mechanism, solve a few crank angles,
// read the rates. Built and run by ctest so this example stays true.
#include <cmath>
#include <cstdio>

#include <kinema/engine/model.hpp>

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "samples/four_bar.toml";
  kinema::Model model = kinema::load_model(path);
  const std::vector<double> angles = {0.1, 0.2, 0.3};  // input values, SI (rad)
  const auto states = kinema::analyse(*model.kinematics, angles, model.mechanism.input.rate,
                                      model.mechanism.input.second_rate);
  for (const kinema::MotionState& state : states) {
    if (state.status != kinema::Status::ok) {
      std::fprintf(stderr, "%s\n", state.message.c_str());
      return 1;
    }
    // Unknowns in file order: theta3, theta4 for the four-bar.
    std::printf("theta2 = %.3f rad: omega3 = %.6f rad/s, alpha3 = %.6f rad/s^2\n", state.input,
                state.qd[0], state.qdd[0]);
  }
  // One value at a time, each from the last (a controller, a simulation step).
  kinema::Workspace workspace(*model.kinematics);
  kinema::MotionState state = states[states.size() - 1];
  if (!workspace.advance(0.31, model.mechanism.input.rate, model.mechanism.input.second_rate, state)) {
    std::fprintf(stderr, "%s\n", "the branch does not reach 0.31 rad");
    return 1;
  }
  std::printf("theta2 = %.3f rad: omega3 = %.6f rad/s (advanced from the last value)\n", state.input, state.qd[0]);
  return 0;
}
