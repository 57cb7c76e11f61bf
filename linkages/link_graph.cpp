// The link graph: ground and the links as bodies, joints as edges, checked for connectivity
// and mobility (Grübler).
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

void LinkageWriter::place_joints() {
  std::set<std::string> names;
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
    const Joint& joint = linkage_.joints[j];
    joint_index_[joint.name] = j;
    const double x = value_of(joint.x, Dimension::length, joint.where, "joint " + joint.name + " x");
    const double y = value_of(joint.y, Dimension::length, joint.where, "joint " + joint.name + " y");
    at_.emplace_back(x, y);
  }
}

void LinkageWriter::make_bodies() {
  Body ground;
  ground.name = "ground";
  bodies_.push_back(ground);
  body_index_["ground"] = 0;
  for (const Link& link : linkage_.links) {
    if (body_index_.count(link.name)) fail(link.where, "duplicate link name \"" + link.name + "\"");
    Body body;
    body.name = link.name;
    body.link = &link;
    for (const std::string& name : link.joints) {
      const auto it = joint_index_.find(name);
      if (it == joint_index_.end()) {
        fail(link.where, "link \"" + link.name + "\" lists joint \"" + name + "\", which is not in [joints]");
      }
      body.joints.push_back(it->second);
      if (linkage_.joints[it->second].kind == Joint::Kind::slider && linkage_.joints[it->second].guide != link.name) {
        if (body.slider >= 0) {
          fail(link.where, "link \"" + link.name + "\" is the block of two sliders (" +
                               linkage_.joints[std::size_t(body.slider)].name + ", " + name +
                               "); kinema takes one slider per block: make the second block a link of its own "
                               "pinned to this one");
        }
        body.slider = static_cast<int>(it->second);
      }
    }
    body_index_[link.name] = bodies_.size();
    bodies_.push_back(body);
  }
}

std::string LinkageWriter::body_list(const std::vector<std::size_t>& bodies) const {
  std::string text;
  for (std::size_t b : bodies) text += (text.empty() ? "" : ", ") + bodies_[b].name;
  return text;
}

void LinkageWriter::make_edges() {
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
    const Joint& joint = linkage_.joints[j];
    std::vector<std::size_t> on;
    if (joint.ground) on.push_back(0);
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      if (std::find(bodies_[b].joints.begin(), bodies_[b].joints.end(), j) != bodies_[b].joints.end()) on.push_back(b);
    }
    if (joint.kind == Joint::Kind::slider) {
      // Its guide may list it too (it slides along that link's line); the block is the other.
      const std::size_t listed = on.size();
      on.erase(std::remove_if(on.begin(), on.end(), [&](std::size_t b) { return bodies_[b].name == joint.guide; }), on.end());
      if (on.empty() && listed > 0) {
        fail(joint.where, "slider \"" + joint.name + "\" slides on \"" + joint.guide +
                              "\", the only link that lists it: its block cannot be its guide; write slider = "
                              "\"ground\" for a fixed guide, or the name of the link that carries the guide");
      }
      if (on.size() != 1) {
        fail(joint.where, on.empty() ? "slider \"" + joint.name + "\" is on no link: list it in the joints of its block"
                                     : "slider \"" + joint.name + "\" is listed by links " + body_list(on) +
                                           "; only its block lists it (its guide is slider = \"...\")");
      }
      const auto guide = body_index_.find(joint.guide);
      if (guide == body_index_.end()) {
        fail(joint.where, "slider \"" + joint.name + "\" slides on \"" + joint.guide +
                              "\", which is not a link; write slider = \"ground\" for a fixed guide or the name of "
                              "the link that carries the guide");
      }
      if (guide->second == on[0]) {
        fail(joint.where, "slider \"" + joint.name + "\" slides on its own block \"" + joint.guide + "\"");
      }
      edges_.push_back(Edge{j, guide->second, on[0], true});
      continue;
    }
    if (on.size() < 2) {
      fail(joint.where, on.empty() ? "joint \"" + joint.name + "\" is on no link: list it in the joints of the links "
                                                               "it joins (or remove it)"
                                   : "joint \"" + joint.name + "\" is used by link " + body_list(on) +
                                         " only; a pin joins two links: add it to the other link's joints, or set "
                                         "ground = true for a fixed pivot");
    }
    // A pin shared by k bodies is k - 1 joints (as Grübler counts it).
    for (std::size_t k = 1; k < on.size(); ++k) edges_.push_back(Edge{j, on[0], on[k], false});
  }
}

void LinkageWriter::check_connected() {
  std::vector<bool> reached(bodies_.size(), false);
  std::vector<std::size_t> queue{0};
  reached[0] = true;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t b = queue[head];
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const Edge& edge = edges_[e];
      if (edge.a != b && edge.b != b) continue;
      const std::size_t other = edge.a == b ? edge.b : edge.a;
      if (reached[other]) continue;
      reached[other] = true;
      edges_[e].in_tree = true;
      bodies_[other].parent_edge = static_cast<int>(e);
      bodies_[other].parent = static_cast<int>(b);
      bodies_[other].depth = bodies_[b].depth + 1;
      queue.push_back(other);
    }
  }
  std::vector<std::size_t> apart;
  for (std::size_t b = 1; b < bodies_.size(); ++b)
    if (!reached[b]) apart.push_back(b);
  if (!apart.empty()) {
    fail(bodies_[apart[0]].link->where,
         std::string(apart.size() == 1 ? "link " : "links ") + body_list(apart) +
             (apart.size() == 1 ? " shares" : " share") +
             " no joint with the rest: no chain of joints leads from ground to it; add the joint that attaches it, "
             "or give a fixed pivot ground = true");
  }
}

void LinkageWriter::check_mobility() {
  const long n = static_cast<long>(bodies_.size()), j = static_cast<long>(edges_.size());
  const long mobility = 3 * (n - 1) - 2 * j;
  if (mobility == 1) return;
  std::ostringstream message;
  message << "the mechanism's mobility is " << mobility << " (Grübler: 3(n - 1) - 2j with n = " << n
          << " bodies, ground included, and j = " << j << " joints: 3*" << (n - 1) << " - 2*" << j << " = " << mobility
          << "), but one driver moves a mechanism of mobility 1; ";
  if (mobility > 1) {
    message << "add " << (mobility - 1) << " constraint(s): a pin between two links, or a binary link with two pins "
            << "(each takes one degree of freedom away)";
  } else {
    message << "it is a structure: remove " << (1 - mobility)
            << " binary link(s) with their two pins, or free a joint (each gives one degree of freedom back)";
  }
  fail(linkage_.driver_where, message.str());
}

}  // namespace kinema::linkage_detail
