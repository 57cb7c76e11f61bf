// Reads a file written as a spatial chain of frames (docs/mechanism-files.md, "Spatial
// chains"): [variables], [frames], [points] and [closures], as written; chains/ builds
// the equations. A file of its own so that each form of mechanism file is read in one place.
#include "readers/file_reader.hpp"

#include <array>
#include <cstddef>

#include "engine/base/units.hpp"
#include "readers/mechanism_file.hpp"  // check_shared_names

namespace kinema::reading {
namespace {

class FramesReader : public FileReader {
 public:
  using FileReader::FileReader;

  // A file written as a spatial chain of frames (docs/mechanism-files.md, "Spatial chains").
  void read(const Node& root, Mechanism& mechanism) const {
    check_keys(root, {"title", "description", "parameters", "input", "variables", "frames", "points", "closures",
                      "output", "problem"},
               "the top level of a spatial chain (a file of frames; vector loops and joints and links are other forms)");
    read_heading(root, mechanism);
    SpatialChain& chain = mechanism.chain.emplace();
    if (has(root, "input")) {
      const Node& input = at(root, "input");
      if (!input.is_string()) fail(input, "input must name a driven variable of [variables], e.g. input = \"theta1\"");
      chain.input = input.value<std::string>().value_or("");
      chain.input_where = where(input);
    }
    read_chain_variables(root, chain);
    read_chain_frames(root, chain);
    read_chain_points(root, chain);
    read_chain_closures(root, chain);
    check_shared_names(mechanism);
  }

 private:
  // A chain's [variables]: the joint variables that drive it, or that its closures find.
  void read_chain_variables(const Node& root, SpatialChain& chain) const {
    if (has(root, "variables")) {
      const Node& table = at(root, "variables");
      if (!table.is_table()) fail(table, "[variables] must be a table of name = { value = \"0 deg\", rate = \"1 rad/s\" }");
      for (const auto& [name, value] : ordered(table)) {
        check_identifier(*value, name, "variable");
        if (!value->is_table()) fail(*value, "variable \"" + name + "\" must be a table { value = \"0 deg\", rate = \"1 rad/s\" }");
        check_keys(*value, {"value", "guess", "rate", "second_rate", "rate_name", "second_rate_name"},
                   "variable \"" + name + "\"");
        ChainVariable variable;
        variable.name = name;
        variable.where = where(*value);
        variable.unknown = has(*value, "guess");
        if (variable.unknown && (has(*value, "value") || has(*value, "rate") || has(*value, "second_rate"))) {
          fail(*value, "variable \"" + name + "\" has a guess, so the closures find it: it takes no value, rate or "
                       "second_rate (those are for a variable that drives the chain)");
        }
        const char* given = variable.unknown ? "guess" : "value";
        if (!has(*value, given)) {
          fail(*value, "variable \"" + name + "\" needs value = \"...\" (at t = 0: an angle or a length), or guess = "
                       "\"...\" for one the closures find");
        }
        const Quantity q = quantity(at(*value, given), given);
        if (q.dimension != Dimension::angle && q.dimension != Dimension::length) {
          fail(at(*value, "value"), "variable \"" + name + "\": value must be an angle (\"30 deg\") or a length (\"0.1 m\")");
        }
        variable.dimension = q.dimension;
        variable.value = q.si_value;
        const Dimension rate = rate_dimension(variable.dimension);
        if (has(*value, "rate")) variable.rate = bounded_rate(at(*value, "rate"), "rate", rate);
        if (has(*value, "second_rate")) {
          variable.second_rate = bounded_rate(at(*value, "second_rate"), "second_rate", rate_dimension(rate));
        }
        variable.rate_name = optional_name(*value, "rate_name");
        variable.second_rate_name = optional_name(*value, "second_rate_name");
        chain.variables.push_back(variable);
      }
    }
  }

  // A chain's [frames]: each with its parent, origin and turns.
  void read_chain_frames(const Node& root, SpatialChain& chain) const {
    const Node& frames = required_table(root, "frames");
    for (const auto& [name, value] : ordered(frames)) {
      check_name(*value, name, "frame");
      if (!value->is_table() || !has(*value, "parent")) {
        fail(*value, "frame \"" + name + "\" must be a table with its parent: { parent = \"E0\", origin = [\"x\", \"y\", "
                                           "\"z\"], turns = [[\"z\", \"theta1\"]] }");
      }
      check_keys(*value, {"parent", "origin", "turns", "joint"}, "frame \"" + name + "\"");
      ChainFrame frame;
      frame.name = name;
      frame.where = where(*value);
      frame.parent = string_value(at(*value, "parent"), "parent");
      if (has(*value, "origin")) read_vector(at(*value, "origin"), "origin", frame.origin);
      if (has(*value, "joint")) {
        const Node& joint = at(*value, "joint");
        frame.joint = string_value(joint, "joint");
        check_name(joint, frame.joint, "joint");
      }
      if (has(*value, "turns")) {
        const Node& turns = at(*value, "turns");
        if (!turns.is_array()) fail(turns, "turns must be a list of [axis, angle] pairs, e.g. [[\"z\", \"theta1\"]]");
        for (const auto& turn : *turns.as_array()) {
          const auto* pair = turn.as_array();
          if (pair == nullptr || pair->size() != 2) {
            fail(turn, "a turn is [axis, angle], e.g. [\"x\", \"-theta4\"] (axis x, y, z or -x, -y, -z)");
          }
          FrameTurn t;
          t.where = where(turn);
          if (!pair->get(0)->is_string()) {  // e.g. a direction vector, [0, 0, 0] among them
            fail(*pair->get(0), "frame \"" + name + "\": a turn's axis is named, \"x\", \"y\" or \"z\" (or \"-x\", ...): "
                                "one of the axes of the frame as turned so far (the parent's for the first turn), "
                                "not a direction vector; a frame whose axis is skew gets a turn first that lines an "
                                "axis up with it");
          }
          t.axis = string_value(*pair->get(0), "axis");
          t.angle = string_value(*pair->get(1), "angle");
          frame.turns.push_back(t);
        }
      }
      chain.frames.push_back(frame);
    }
    if (chain.frames.empty()) fail(frames, "[frames] is empty: name each frame with its parent");
  }

  // A chain's [points], each in a frame.
  void read_chain_points(const Node& root, SpatialChain& chain) const {
    if (has(root, "points")) {
      const Node& table = at(root, "points");
      if (!table.is_table()) fail(table, "[points] must be a table of name = { frame = \"E3\", at = [\"x\", \"y\", \"z\"] }");
      for (const auto& [name, value] : ordered(table)) {
        check_name(*value, name, "point");
        if (!value->is_table() || !has(*value, "frame")) {
          fail(*value, "point \"" + name + "\" must be written { frame = \"E3\", at = [\"x\", \"y\", \"z\"] }");
        }
        check_keys(*value, {"frame", "at"}, "point \"" + name + "\"");
        ChainPoint point;
        point.name = name;
        point.where = where(*value);
        point.frame = string_value(at(*value, "frame"), "frame");
        if (has(*value, "at")) read_vector(at(*value, "at"), "at", point.at);
        chain.points.push_back(point);
      }
    }
  }

  // A chain's [closures]: two points a fixed distance apart.
  void read_chain_closures(const Node& root, SpatialChain& chain) const {
    if (has(root, "closures")) {
      const Node& table = at(root, "closures");
      if (!table.is_table()) fail(table, "[closures] must be a table of name = { between = [\"B\", \"C\"], length = \"L3\" }");
      for (const auto& [name, value] : ordered(table)) {
        check_name(*value, name, "closure");
        if (!value->is_table() || !has(*value, "between") || !has(*value, "length")) {
          fail(*value, "closure \"" + name + "\" must be written { between = [\"B\", \"C\"], length = \"L3\" } (two points "
                       "a fixed distance apart)");
        }
        check_keys(*value, {"between", "length"}, "closure \"" + name + "\"");
        const auto* pair = at(*value, "between").as_array();
        if (pair == nullptr || pair->size() != 2) fail(at(*value, "between"), "between must name two points, e.g. [\"B\", \"C\"]");
        ChainClosure closure;
        closure.name = name;
        closure.where = where(*value);
        closure.from = string_value(*pair->get(0), "between");
        closure.to = string_value(*pair->get(1), "between");
        closure.length = string_value(at(*value, "length"), "length");
        chain.closures.push_back(closure);
      }
    }
  }

  // A vector in a frame's axes ["x", "y", "z"]: quantities or formulas.
  void read_vector(const Node& value, const std::string& what, std::array<std::string, 3>& out) const {
    const auto* list = value.as_array();
    if (list == nullptr || list->size() != 3) {
      fail(value, what + " must be three components [\"x\", \"y\", \"z\"] in the frame's axes, e.g. "
                         "[\"0 m\", \"L2\", \"0 m\"]");
    }
    for (std::size_t c = 0; c < 3; ++c) out[c] = string_value(*list->get(c), what);
  }
};

}  // namespace

void read_spatial_frames(const std::string& file, const Node& root, Mechanism& mechanism) {
  FramesReader(file).read(root, mechanism);
}

}  // namespace kinema::reading
