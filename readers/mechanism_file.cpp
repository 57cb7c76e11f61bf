// The mechanism file's front door (mechanism_file.hpp): the file read within its size
// limit, its form told by its sections and handed to that form's reader
// (vector_loop_reader.cpp, joints_reader.cpp, frames_reader.cpp; what they share:
// file_reader.hpp), and the one name space of parameters, input and unknowns checked.
#include "readers/mechanism_file.hpp"

#include <map>

#include "engine/base/errors.hpp"
#include "readers/file_reader.hpp"

namespace kinema {

// Parameters, the input and the unknowns share one name space (they are symbols in formulas).
void check_shared_names(const Mechanism& mechanism) {
  std::map<std::string, SourceLocation> seen;
  auto add = [&](const std::string& name, const SourceLocation& at, const std::string& what) {
    auto [it, inserted] = seen.emplace(name, at);
    if (!inserted) {
      throw InputError(at.str() + ": duplicate name \"" + name + "\" (" + what +
                       "): it is already defined at " + it->second.str() + "; rename one of them");
    }
  };
  for (const auto& p : mechanism.parameters) add(p.name, p.where, "parameter");
  if (mechanism.chain) {
    for (const auto& v : mechanism.chain->variables) {
      add(v.name, v.where, "variable");
      if (!v.rate_name.empty()) add(v.rate_name, v.where, "rate name");
      if (!v.second_rate_name.empty()) add(v.second_rate_name, v.where, "second rate name");
    }
    return;
  }
  add(mechanism.input.name, mechanism.input.where, "input");
  for (const auto& u : mechanism.unknowns) add(u.name, u.where, "unknown");
}

Mechanism read_mechanism_text(const std::string& text, const std::string& name) {
  const toml::table root = reading::FileReader(name).parse(text);
  Mechanism mechanism;
  mechanism.source_file = name;
  // The form is told by the sections only it has.
  if (root.contains("frames") || root.contains("variables")) {
    reading::read_spatial_frames(name, root, mechanism);
  } else if (root.contains("joints") || root.contains("links") || root.contains("driver")) {
    reading::read_joints_and_links(name, root, mechanism);
  } else {
    reading::read_vector_loops(name, root, mechanism);
  }
  return mechanism;
}

Mechanism read_mechanism_file(const std::string& path) {
  const std::string text = reading::read_text_file(path, kMaxMechanismFileBytes, "mechanism file");
  return read_mechanism_text(text, path);
}

}  // namespace kinema
