// Angles and coordinates: each link oriented along the spanning tree from ground, each
// slider's coordinate named, the unknowns with their sketch values as guesses.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

std::string LinkageWriter::default_angle_name(const Body& body) const {
  return std::isdigit(static_cast<unsigned char>(body.name[0])) ? "theta" + body.name : "theta_" + body.name;
}

// Link angles, slider coordinates and the input are symbols: parameters made here
// must not take their names.
void LinkageWriter::reserve_names() {
  if (!m_.input.name.empty()) taken_.insert(m_.input.name);
  for (std::size_t b = 1; b < bodies_.size(); ++b) {
    const Body& body = bodies_[b];
    if (body.slider < 0) taken_.insert(body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name);
  }
  for (const Joint& joint : linkage_.joints)
    if (joint.kind == Joint::Kind::slider) taken_.insert(joint.coordinate.empty() ? "s_" + joint.name : joint.coordinate);
}

// Links with angles of their own first, then the driver's name, then slider blocks
// (whose angles are their guides').
void LinkageWriter::orient_bodies() {
  bodies_[0].oriented = true;
  bodies_[0].angle = "0";
  for (std::size_t b = 1; b < bodies_.size(); ++b)
    if (bodies_[b].slider < 0) orient(b, 0);
  if (driver_slider_ < 0) {
    Body& body = bodies_[driver_body_];
    if (m_.input.name.empty()) m_.input.name = body.angle;
    body.angle = m_.input.name;
  }
  for (std::size_t b = 1; b < bodies_.size(); ++b) orient(b, 0);
}

// The guide link, when it lists the slider (then the slider runs along the line from
// the guide's first joint), else nullptr.
const LinkageWriter::Body* LinkageWriter::listing_guide(std::size_t j) const {
  const auto it = body_index_.find(linkage_.joints[j].guide);
  if (it == body_index_.end() || it->second == 0) return nullptr;
  const Body& guide = bodies_[it->second];
  return std::find(guide.joints.begin(), guide.joints.end(), j) != guide.joints.end() ? &guide : nullptr;
}

double LinkageWriter::slider_direction(std::size_t j) {
  const Joint& joint = linkage_.joints[j];
  if (!joint.angle.empty()) {
    const double angle = value_of(joint.angle, Dimension::angle, joint.where, "slider " + joint.name + " angle");
    if (!(std::fabs(angle) <= from_degrees(kMaxAngleDegrees))) {  // as for the input
      fail(joint.where, "slider \"" + joint.name + "\": angle = \"" + joint.angle +
                            "\" is past 1e9 deg, where its direction is lost to rounding; give the direction of its "
                            "line within a turn (e.g. \"90 deg\")");
    }
    return angle;
  }
  const Body* guide = listing_guide(j);
  if (guide == nullptr || guide->joints[0] == j || std::abs(at_[j] - at_[guide->joints[0]]) < 1e-12) {
    fail(joint.where, "slider \"" + joint.name + "\" needs angle = \"...\", the direction of its line in the sketch "
                      "(e.g. \"90 deg\"); or list it in the joints of its guide link, after the first: it then "
                      "slides along the line from that joint");
  }
  return std::arg(at_[j] - at_[guide->joints[0]]);
}

void LinkageWriter::orient(std::size_t b, int depth) {
  Body& body = bodies_[b];
  if (body.oriented) return;
  if (depth > static_cast<int>(bodies_.size())) {
    fail(body.link->where, "link \"" + body.name + "\": its slider's guides form a cycle; one of them must be a "
                                                  "link with an angle of its own");
  }
  if (body.slider >= 0) {
    const std::size_t j = static_cast<std::size_t>(body.slider);
    const std::size_t guide = body_index_.at(linkage_.joints[j].guide);
    orient(guide, depth + 1);
    const Body& g = bodies_[guide];
    body.angle0 = slider_direction(j);
    body.angle = g.angle;
    body.offset = wrapped(g.offset + body.angle0 - g.angle0);
  } else if (body.joints.size() < 2) {
    // A link with one joint carries the guide of a slider (a crank with a block sliding
    // on it): its angle is the direction of that line.
    int guided = -1;
    for (std::size_t j = 0; j < linkage_.joints.size() && guided < 0; ++j)
      if (linkage_.joints[j].kind == Joint::Kind::slider && linkage_.joints[j].guide == body.name) guided = static_cast<int>(j);
    if (guided < 0 || body.joints.empty()) {
      fail(body.link->where, "link \"" + body.name + "\" has " + std::to_string(body.joints.size()) +
                                 " joint; a link joins at least two (a crank that only guides a slider: its pivot, "
                                 "and the slider names it, slider = \"" + body.name + "\")");
    }
    body.angle0 = slider_direction(std::size_t(guided));
    body.angle = body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name;
  } else {
    const Point2 d = at_[body.joints[1]] - at_[body.joints[0]];
    if (std::abs(d) <= 1e-12 * (1 + std::abs(at_[body.joints[0]]))) {
      fail(body.link->where, "link \"" + body.name + "\": its first two joints, " + linkage_.joints[body.joints[0]].name +
                                 " and " + linkage_.joints[body.joints[1]].name +
                                 ", are at the same place in the sketch; its angle is the direction from the first "
                                 "to the second: list a joint elsewhere second");
    }
    body.angle0 = std::arg(d);
    body.angle = body.link->angle_name.empty() ? default_angle_name(body) : body.link->angle_name;
  }
  body.oriented = true;
}

void LinkageWriter::name_coordinates() {
  slider_coordinate_.assign(linkage_.joints.size(), "");
  slider_value0_.assign(linkage_.joints.size(), 0.0);
  for (const Edge& e : edges_) {
    if (!e.slider) continue;
    const Joint& joint = linkage_.joints[e.joint];
    slider_coordinate_[e.joint] = joint.coordinate.empty() ? "s_" + joint.name : joint.coordinate;
    const Point2 from = through0(e.joint);
    slider_value0_[e.joint] = std::real((at_[e.joint] - from) * std::polar(1.0, -slider_direction(e.joint)));
    const double off = std::imag((at_[e.joint] - from) * std::polar(1.0, -slider_direction(e.joint)));
    if (std::fabs(off) > kSketchTolerance * std::max(std::abs(at_[e.joint] - from), 1e-9) + 1e-9) {
      fail(joint.where, "slider \"" + joint.name + "\": its place in the sketch is " + format_significant(std::fabs(off)) +
                            " m off its line (through the point given and at its angle); put it on the line");
    }
  }
  // The input: a crank's angle or a slider's coordinate.
  Input& input = m_.input;
  if (driver_slider_ >= 0) {
    const Joint& joint = linkage_.joints[std::size_t(driver_slider_)];
    if (input.name.empty()) input.name = slider_coordinate_[std::size_t(driver_slider_)];
    slider_coordinate_[std::size_t(driver_slider_)] = input.name;
    if (input.rate_name.empty()) input.rate_name = joint.rate_name;
    if (input.second_rate_name.empty()) input.second_rate_name = joint.second_rate_name;
  } else {
    const Body& body = bodies_[driver_body_];
    if (input.rate_name.empty()) input.rate_name = body.link->rate_name;
    if (input.second_rate_name.empty()) input.second_rate_name = body.link->second_rate_name;
  }
  for (std::size_t b = 1; b < bodies_.size(); ++b) {
    const Body& body = bodies_[b];
    if (body.slider >= 0 || b == driver_body_) continue;
    Unknown u;
    u.name = body.angle;
    u.dimension = Dimension::angle;
    u.guess = body.angle0;
    u.rate_name = body.link->rate_name;
    u.second_rate_name = body.link->second_rate_name;
    u.where = body.link->where;
    m_.unknowns.push_back(u);
  }
  for (const Edge& e : edges_) {
    if (!e.slider || static_cast<int>(e.joint) == driver_slider_) continue;
    const Joint& joint = linkage_.joints[e.joint];
    Unknown u;
    u.name = slider_coordinate_[e.joint];
    u.dimension = Dimension::length;
    u.guess = slider_value0_[e.joint];
    u.rate_name = joint.rate_name;
    u.second_rate_name = joint.second_rate_name;
    u.where = joint.where;
    m_.unknowns.push_back(u);
  }
}

// The point a slider's coordinate is measured from, in the sketch.
Point2 LinkageWriter::through0(std::size_t j) {
  const Joint& joint = linkage_.joints[j];
  if (joint.through_x.empty()) {
    const Body* guide = listing_guide(j);
    return guide != nullptr ? at_[guide->joints[0]] : at_[j];
  }
  return {value_of(joint.through_x, Dimension::length, joint.where, "slider " + joint.name + " through x"),
          value_of(joint.through_y, Dimension::length, joint.where, "slider " + joint.name + " through y")};
}

}  // namespace kinema::linkage_detail
