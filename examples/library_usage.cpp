// Using kinema as a library: load a mechanism, solve it at a few crank angles, read
// the results by name. Built and run by ctest against an installed kinema
// (find_package(kinema)), which also checks its omega3 against `kinema eval`.
#include <cstdio>
#include <string>
#include <vector>

#include <kinema/kinema.hpp>

int main(int argc, char** argv) {
  const char* path = argc > 1 ? argv[1] : "samples/four_bar.toml";
  try {
    const kinema::MechanismModel four_bar(path);
    std::printf("%s: input %s, unknowns", four_bar.title().c_str(), four_bar.names().input.c_str());
    for (const std::string& name : four_bar.names().unknowns) std::printf(" %s", name.c_str());
    std::printf("\n");

    // Input values with their units, solved in order on one branch; the rates are the file's.
    const std::vector<std::string> angles = {"10 deg", "20 deg", "30 deg"};
    const std::vector<kinema::Solution> solutions = four_bar.solve(angles);
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const kinema::Solution& at = solutions[i];
      if (!at.ok()) {  // does not assemble, or a toggle: kinema says why
        std::fprintf(stderr, "%s\n", at.message().c_str());
        return 1;
      }
      // Results in SI, by the names the file gives.
      const kinema::PointResult& p = at.point("P");
      std::printf("theta2 = %s: omega3 = %.6g rad/s, alpha3 = %.6g rad/s^2, vP = (%.4f, %.4f) m/s\n",
                  angles[i].c_str(), at.rate("omega3"), at.second_rate("alpha3"), p.velocity[0], p.velocity[1]);
    }
  } catch (const kinema::Error& error) {  // a bad file, unit or name: what and where
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
