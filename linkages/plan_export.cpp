// The solving plan handed on (engine/constraints/solving_plan.hpp): joints, links, bodies,
// sliders, pins and dyads as numbers, and the assemblies the file states.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

// The joints and links by name, and the numbers the closed-form solution needs
// (engine/numeric/dyad_positions), the same lengths and angles as the loops', with the
// sketch the dyads' assemblies are read from (engine/numeric/assemblies).
void LinkageWriter::export_plan() {
  SolvingPlan& f = plan_;
  const auto unknown_index = [&](const std::string& name) {
    for (std::size_t i = 0; i < m_.unknowns.size(); ++i)
      if (m_.unknowns[i].name == name) return static_cast<int>(i);
    return -1;
  };
  for (const Joint& joint : linkage_.joints)
    f.joints.push_back({joint.name, joint.kind == Joint::Kind::slider, joint.ground, joint.where});
  for (std::size_t b = 1; b < bodies_.size(); ++b) {
    const Link& link = *bodies_[b].link;
    f.links.push_back({link.name, link.angle_name.empty() ? default_angle_name(bodies_[b]) : link.angle_name, link.where});
  }
  f.bodies.assign(bodies_.size(), {});
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j)
    if (linkage_.joints[j].ground) f.bodies[0].points.push_back({j, at_[j]});
  for (std::size_t b = 1; b < bodies_.size(); ++b) {
    const Body& body = bodies_[b];
    SolvingPlan::Body& frame = f.bodies[b];
    frame.sketch_origin = at_[body.joints[0]];
    frame.sketch_angle = body.angle0;
    for (std::size_t j : body.joints) {
      Point2 v;
      if (j != body.joints[0] && std::abs(at_[j] - at_[body.joints[0]]) > 1e-12 * (1 + std::abs(at_[body.joints[0]]))) {
        const double d = length_value(body, body.joints[0], j);
        v = std::polar(d, offset(body, j, d));
      }
      frame.points.push_back({j, v});
    }
    if (body.slider >= 0) {
      frame.guide = static_cast<int>(body_index_.at(linkage_.joints[std::size_t(body.slider)].guide));
      frame.offset = wrapped(body.angle0 - bodies_[std::size_t(frame.guide)].angle0);
    } else if (b != driver_body_ || driver_slider_ >= 0) {
      frame.unknown = unknown_index(body.angle);
    }
  }
  std::vector<int> edge_ref(edges_.size());
  for (std::size_t k = 0; k < edges_.size(); ++k) {
    const Edge& e = edges_[k];
    if (!e.slider) {
      edge_ref[k] = static_cast<int>(f.pins.size());
      f.pins.push_back({e.joint, e.a, e.b});
      continue;
    }
    SolvingPlan::Slider s;
    s.joint = e.joint;
    s.guide = e.a;
    s.block = e.b;
    const Body& guide = bodies_[e.a];
    const Point2 t = through0(e.joint);
    s.through = e.a == 0 ? t : (t - at_[guide.joints[0]]) * std::polar(1.0, -guide.angle0);
    s.direction = wrapped(slider_direction(e.joint) - guide.angle0);
    s.unknown = static_cast<int>(e.joint) == driver_slider_ ? -1 : unknown_index(slider_coordinate_[e.joint]);
    if (static_cast<int>(e.joint) == driver_slider_) f.driver_slider = static_cast<int>(f.sliders.size());
    edge_ref[k] = -1 - static_cast<int>(f.sliders.size());
    f.sliders.push_back(s);
  }
  f.driver_body = driver_body_;
  f.sketch_input = driver_slider_ >= 0 ? slider_value0_[std::size_t(driver_slider_)] : bodies_[driver_body_].angle0;
  f.closed_form = true;
  for (const SolvingPlan::Step& group : plan_.steps) f.closed_form = f.closed_form && group.kind != "group";
  for (const auto& [first, second, outer1, inner, outer2] : dyad_edges_) {
    SolvingPlan::Dyad d;
    d.first = first;
    d.second = second;
    d.outer_first = edge_ref[outer1];
    d.inner = edge_ref[inner];
    d.outer_second = edge_ref[outer2];
    // A slider inside a dyad is solved here only between two pins (RTR).
    if (d.inner < 0 && (d.outer_first < 0 || d.outer_second < 0)) f.closed_form = false;
    f.dyads.push_back(d);
  }
  check_assembly_joints();
  if (f.closed_form) state_assemblies();
}

// A joint may state its dyad's assembly only if it is a dyad's middle joint.
void LinkageWriter::check_assembly_joints() const {
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
    const Joint& joint = linkage_.joints[j];
    if (joint.assembly.empty()) continue;
    bool inner = false;
    for (const auto& edges : dyad_edges_) inner = inner || edges_[edges[3]].joint == j;
    if (!inner) {
      std::string middles;
      for (const auto& edges : dyad_edges_) middles += (middles.empty() ? "" : ", ") + linkage_.joints[edges_[edges[3]].joint].name;
      fail(joint.where, "joint \"" + joint.name + "\" states an assembly, but it is not the middle joint of a dyad" +
                            (middles.empty() ? std::string(" (this mechanism has no dyads)")
                                             : " (the middle joints: " + middles + ")") +
                            "; state it on the middle joint of the dyad it chooses");
    }
    if (!plan_.closed_form) {
      fail(joint.where, "joint \"" + joint.name + "\" states an assembly, but its links are solved by Newton with the "
                        "others (not dyad by dyad); draw the sketch on the assembly wanted instead");
    }
  }
}

// Dyads whose middle joint states "left of X-Y" or "right of X-Y": the statement read
// into the plan (which assembly that is, engine/numeric/assemblies reads at the sketch).
void LinkageWriter::state_assemblies() {
  for (std::size_t k = 0; k < plan_.dyads.size(); ++k) {
    SolvingPlan::Dyad& d = plan_.dyads[k];
    const Joint& joint = linkage_.joints[edges_[dyad_edges_[k][3]].joint];
    if (joint.assembly.empty()) continue;
    const std::string& text = joint.assembly;
    const std::string what = "joint \"" + joint.name + "\": assembly = \"" + text + "\"";
    const std::size_t of = text.find(" of ");
    const std::size_t dash = text.find('-', of == std::string::npos ? 0 : of);
    const std::string side = of == std::string::npos ? "" : text.substr(0, of);
    if ((side != "left" && side != "right") || dash == std::string::npos) {
      fail(joint.where, what + " is not a side: write \"left of B-D\" or \"right of B-D\" (the side of the line "
                        "from joint B to joint D that " + joint.name + " is on, as the driver is sketched)");
    }
    const std::string from = text.substr(of + 4, dash - of - 4), to = text.substr(dash + 1);
    for (const std::string& name : {from, to}) {
      if (joint_index_.count(name) == 0) fail(joint.where, what + ": there is no joint \"" + name + "\"");
    }
    if (from == to) fail(joint.where, what + ": a line needs two different joints");
    d.stated = text;
    d.left = side == "left";
    d.from = joint_index_.at(from);
    d.to = joint_index_.at(to);
    plan_.steps[k + 1].assembly = joint.name + " " + text;
  }
}

}  // namespace kinema::linkage_detail
