// What a dyad-by-dyad derivation is (engine/symbolic/dyad_method derives it): the
// methods, and the relations of each step as data. Its own header so that the printers,
// which show a derivation, include no header of the derivation itself.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kinema {

enum class DerivationMethod { loops, relative_velocity, joint_coordinates };

/// "loops", "relative-velocity", "joint-coordinates" (as --method takes them).
const char* method_name(DerivationMethod method);
std::optional<DerivationMethod> find_method(std::string_view name);
std::vector<std::string> method_names();

struct MethodRelation {
  enum class Kind {
    statement,  ///< A relation as the method writes it (text, latex), before components.
    component,  ///< left = right, one scalar equation (text: "x" or "y", or what it is).
    solution,   ///< left (a symbol) = right: a rate solved, or a joint's velocity defined.
  };
  Kind kind = Kind::statement;
  std::string text, latex;
  GiNaC::ex left, right;
};

struct MethodStep {
  std::string heading;  ///< "driver: link 1 (A)", "dyad 1, RRR: links 2, 3; joints B, C, D".
  std::string note;     ///< Why the step is written in another form (empty if not).
  std::vector<MethodRelation> velocity, acceleration;
};

struct DyadDerivation {
  DerivationMethod method = DerivationMethod::relative_velocity;
  std::vector<MethodStep> steps;
  /// The symbols a relation may use besides the system's (joint coordinates x_B, y_B,
  /// velocities v_Bx, v_By, accelerations a_Bx, a_By; a slider joint's point on its
  /// guide v_B_3x ...), by name.
  std::map<std::string, GiNaC::realsymbol> symbols;
};

}  // namespace kinema
