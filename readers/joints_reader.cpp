// Reads a file written as joints and links (docs/mechanism-files.md, "Joints and links"):
// [joints], [links], [driver] and [points], as written; linkages/ finds the loops and the
// dyads. A file of its own so that each form of mechanism file is read in one place.
#include "readers/file_reader.hpp"

#include <algorithm>
#include <cstddef>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/base/user_text.hpp"
#include "readers/mechanism_file.hpp"  // kMaxJoints, kMaxLinks

namespace kinema::reading {
namespace {

class JointsReader : public FileReader {
 public:
  using FileReader::FileReader;

  // A file written as joints and links (docs/mechanism-files.md, "Joints and links"), as
  // written: linkages/ finds its loops and dyads.
  void read(const Node& root, Mechanism& mechanism) const {
    check_keys(root, {"title", "description", "parameters", "driver", "joints", "links", "points", "output", "problem"},
               "the top level of a joints-and-links file (vector loops go in another file: [input], [unknowns], "
               "[loops])");
    read_heading(root, mechanism);
    Linkage& linkage = mechanism.linkage.emplace();
    read_joints(root, linkage);
    read_links(root, linkage);
    read_driver(root, mechanism);
    read_link_points(root, linkage);
    // No check_shared_names here: the names are checked with those the front end adds (linkages/).
  }

 private:
  // A sketch position ["x", "y"]: two quantities or formulas of the parameters.
  void read_position(const Node& value, const std::string& what, std::string& x, std::string& y) const {
    const auto* list = value.as_array();
    if (list == nullptr || list->size() != 2) {
      fail(value, what + " must be a position [\"x\", \"y\"], e.g. [\"0.3 m\", \"Lb\"]");
    }
    x = string_value(*list->get(0), what + " x");
    y = string_value(*list->get(1), what + " y");
  }

  // [joints] or [links], refused past its limit.
  const Node& bounded_table(const Node& root, const std::string& key, std::size_t limit) const {
    const Node& table = required_table(root, key);
    if (table.as_table()->size() > limit) {
      fail(table, "[" + key + "] has " + std::to_string(table.as_table()->size()) + " " + key + "; kinema takes up to " +
                      std::to_string(limit) + " (a mechanism has tens)");
    }
    return table;
  }

  void read_joints(const Node& root, Linkage& linkage) const {
    const Node& table = bounded_table(root, "joints", kMaxJoints);
    for (const auto& [name, value] : ordered(table)) {
      check_identifier(*value, name, "joint");
      if (!value->is_table()) {
        fail(*value, "joint \"" + name + "\" must be a table, e.g. " + name +
                         " = { at = [\"0.1 m\", \"0.2 m\"] } (add ground = true for a fixed pivot)");
      }
      check_keys(*value,
                 {"at", "ground", "slider", "angle", "through", "coordinate", "rate_name", "second_rate_name", "assembly"},
                 "joint \"" + name + "\"");
      Joint joint;
      joint.name = name;
      joint.where = where(*value);
      if (!has(*value, "at")) fail(*value, "joint \"" + name + "\" needs at = [\"x\", \"y\"] (its place in the sketch)");
      read_position(at(*value, "at"), "at", joint.x, joint.y);
      if (has(*value, "ground")) {
        const Node& ground = at(*value, "ground");
        if (!ground.is_boolean()) fail(ground, "ground must be true or false");
        joint.ground = ground.as_boolean()->get();
      }
      if (has(*value, "assembly")) {
        joint.assembly = string_value(at(*value, "assembly"), "assembly");
        // Left out, the sketch's side holds; empty, it would silently say the same.
        if (joint.assembly.find_first_not_of(" \t") == std::string::npos) {
          fail(at(*value, "assembly"), "joint \"" + joint.name + "\": assembly = \"" + joint.assembly +
                                "\" is empty; write \"left of B-D\" or \"right of B-D\" (the side of the line between "
                                "two joints), or leave assembly out for the sketch's side");
        }
      }
      if (has(*value, "slider")) {
        joint.kind = Joint::Kind::slider;
        joint.guide = string_value(at(*value, "slider"), "slider");
        if (joint.ground) {
          fail(*value, "joint \"" + name + "\" is a slider and a ground pivot; a slider on a fixed guide is written "
                           "slider = \"ground\" (without ground = true)");
        }
        if (has(*value, "angle")) joint.angle = string_value(at(*value, "angle"), "angle");
        if (has(*value, "through")) read_position(at(*value, "through"), "through", joint.through_x, joint.through_y);
        if (has(*value, "coordinate")) {
          joint.coordinate = string_value(at(*value, "coordinate"), "coordinate");
          check_identifier(at(*value, "coordinate"), joint.coordinate, "slider coordinate");
        }
        joint.rate_name = optional_name(*value, "rate_name");
        joint.second_rate_name = optional_name(*value, "second_rate_name");
      } else {
        for (const char* key : {"angle", "through", "coordinate", "rate_name", "second_rate_name"}) {
          if (has(*value, key)) {
            fail(at(*value, key), std::string(key) + " belongs to a slider; joint \"" + name +
                                      "\" is a pin (add slider = \"<guide link>\" to make it a slider)");
          }
        }
      }
      linkage.joints.push_back(joint);
    }
    if (linkage.joints.empty()) fail(table, "[joints] is empty: name the joints of the mechanism as in its figure");
  }

  // Link names may start with a digit, as links are numbered in figures ("2", "3").
  void check_link_name(const Node& value, const std::string& name) const {
    if (!is_identifier("L" + name) || name == "ground") {
      fail(value, "link name \"" + one_line(name) + "\" is not valid (letters, digits, _; \"ground\" is the frame)");
    }
  }

  void read_links(const Node& root, Linkage& linkage) const {
    const Node& table = bounded_table(root, "links", kMaxLinks);
    for (const auto& [name, value] : ordered(table)) {
      check_link_name(*value, name);
      Link link;
      link.name = name;
      link.where = where(*value);
      const Node* joints = value;
      if (value->is_table()) {
        check_keys(*value, {"joints", "length", "lengths", "angles", "angle", "rate_name", "second_rate_name"},
                   "link \"" + name + "\"");
        if (!has(*value, "joints")) fail(*value, "link \"" + name + "\" needs joints = [\"B\", \"C\", ...]");
        joints = &at(*value, "joints");
        if (has(*value, "angle")) {
          link.angle_name = string_value(at(*value, "angle"), "angle");
          check_identifier(at(*value, "angle"), link.angle_name, "link angle");
        }
        link.rate_name = optional_name(*value, "rate_name");
        link.second_rate_name = optional_name(*value, "second_rate_name");
      }
      if (!joints->is_array()) fail(*joints, "the joints of link \"" + name + "\" must be a list, e.g. [\"B\", \"C\"]");
      for (const auto& joint : *joints->as_array()) {
        const std::string joint_name = string_value(joint, "joints");
        if (std::find(link.joints.begin(), link.joints.end(), joint_name) != link.joints.end()) {
          fail(joint, "link \"" + name + "\" lists joint \"" + one_line(joint_name) + "\" twice");
        }
        link.joints.push_back(joint_name);
      }
      if (value->is_table() && has(*value, "length")) {
        if (link.joints.size() != 2) {
          fail(at(*value, "length"), "length is for a link with two joints; link \"" + name + "\" has " +
                                         std::to_string(link.joints.size()) +
                                         ": write lengths = { \"C-D\" = \"...\", ... }");
        }
        link.lengths.push_back({{link.joints[0], link.joints[1]}, string_value(at(*value, "length"), "length")});
      }
      if (value->is_table() && has(*value, "lengths")) {
        const Node& lengths = at(*value, "lengths");
        if (!lengths.is_table()) fail(lengths, "lengths must be a table such as { \"C-D\" = \"CD\" }");
        for (const auto& [pair, length] : ordered(lengths)) {
          const auto dash = pair.find('-');
          const std::string a = pair.substr(0, dash), b = dash == std::string::npos ? "" : pair.substr(dash + 1);
          const auto on_link = [&](const std::string& j) {
            return std::find(link.joints.begin(), link.joints.end(), j) != link.joints.end();
          };
          if (dash == std::string::npos || !on_link(a) || !on_link(b) || a == b) {
            fail(*length, "\"" + one_line(pair) + "\" is not two joints of link \"" + name +
                              "\" joined by '-' (e.g. \"" + link.joints[0] + "-" +
                              (link.joints.size() > 1 ? link.joints[1] : std::string("B")) + "\")");
          }
          link.lengths.push_back({{a, b}, string_value(*length, pair)});
        }
      }
      if (value->is_table() && has(*value, "angles")) {
        const Node& angles = at(*value, "angles");
        if (!angles.is_table()) fail(angles, "angles must be a table such as { D = \"180 deg\" }");
        for (const auto& [joint, angle] : ordered(angles)) {
          if (link.joints.size() < 3 || std::find(link.joints.begin() + 2, link.joints.end(), joint) == link.joints.end()) {
            fail(*angle, "angles of link \"" + name + "\" are given for its joints after the second (the angle at its "
                         "first joint from its second to that joint); \"" + one_line(joint) + "\" is not one");
          }
          link.angles.push_back({joint, string_value(*angle, joint)});
        }
      }
      linkage.links.push_back(link);
    }
    if (linkage.links.empty()) fail(table, "[links] is empty: list each moving link and its joints");
  }

  void read_driver(const Node& root, Mechanism& mechanism) const {
    const Node& table = required_table(root, "driver");
    check_keys(table, {"link", "slider", "name", "value", "values", "sweep", "rate", "second_rate", "rate_name",
                       "second_rate_name"},
               "[driver]");
    Linkage& linkage = *mechanism.linkage;
    Input& input = mechanism.input;
    input.where = where(table);
    linkage.driver_where = where(table);
    if (has(table, "link") == has(table, "slider")) {
      fail(table, "[driver] needs either link = \"2\" (a crank: its angle is the input) or slider = \"F\" "
                  "(a slider joint: its coordinate is the input)");
    }
    if (has(table, "link")) linkage.driver_link = string_value(at(table, "link"), "link");
    if (has(table, "slider")) linkage.driver_slider = string_value(at(table, "slider"), "slider");
    if (has(table, "name")) {
      input.name = string_value(at(table, "name"), "name");
      check_identifier(at(table, "name"), input.name, "driver");
    }
    // A crank turns through angles, a slider moves through lengths: say so before the
    // rates are read in the units the values imply.
    const Dimension kind = has(table, "link") ? Dimension::angle : Dimension::length;
    for (const char* key : {"value", "values"}) {
      if (!has(table, key)) continue;
      const Node& node = at(table, key);
      const auto check = [&](const Node& value) {
        const Quantity q = quantity(value, key);
        if (q.dimension != kind && q.dimension != Dimension::number) {
          fail(value, std::string("the driver is a ") + (kind == Dimension::angle ? "crank: its values are angles, e.g. \"30 deg\""
                                                                                  : "slider: its values are lengths, e.g. \"0.2 m\""));
        }
      };
      if (node.is_array()) {
        for (const auto& value : *node.as_array()) check(value);
      } else {
        check(node);
      }
    }
    read_motion(table, "[driver]", input);
  }

  void read_link_points(const Node& root, Linkage& linkage) const {
    if (!has(root, "points")) return;
    const Node& table = at(root, "points");
    if (!table.is_table()) fail(table, "[points] must be a table of name = { link = \"3\", at = [\"x\", \"y\"] }");
    for (const auto& [name, value] : ordered(table)) {
      check_name(*value, name, "point");
      if (!value->is_table() || !has(*value, "link") || !has(*value, "at")) {
        fail(*value, "point \"" + name + "\" must be written { link = \"3\", at = [\"x\", \"y\"] } (the link it is "
                                          "on and its place in the sketch)");
      }
      check_keys(*value, {"link", "at"}, "point \"" + name + "\"");
      LinkPoint point;
      point.name = name;
      point.where = where(*value);
      point.link = string_value(at(*value, "link"), "link");
      read_position(at(*value, "at"), "at", point.x, point.y);
      linkage.points.push_back(point);
    }
  }
};

}  // namespace

void read_joints_and_links(const std::string& file, const Node& root, Mechanism& mechanism) {
  JointsReader(file).read(root, mechanism);
}

}  // namespace kinema::reading
