// The loops and points as sums of terms: one loop per joint outside the spanning tree,
// each the two paths from ground to that joint; each moving joint and link point as a point.
#include "linkages/linkage_writer.hpp"

#include <algorithm>

namespace kinema::linkage_detail {

LinkageWriter::Path LinkageWriter::position(std::size_t b, std::size_t j) {
  Path path = reference(b);
  if (b == 0) path.steps.push_back({-1, ground_point(linkage_.joints[j].x, linkage_.joints[j].y, linkage_.joints[j].name,
                                                     linkage_.joints[j].where)});
  else path.steps.push_back({-1, body_vector(b, j)});
  return path;
}

// The body's first joint, from ground along the tree.
LinkageWriter::Path LinkageWriter::reference(std::size_t b) {
  if (b == 0) return {};
  const Body& body = bodies_[b];
  const Edge& e = edges_[std::size_t(body.parent_edge)];
  const std::size_t parent = std::size_t(body.parent);
  Path path;
  std::vector<Term> terms;
  if (!e.slider) {
    path = position(parent, e.joint);
    terms = negated(body_vector(b, e.joint));
  } else if (parent == e.a) {  // guide -> block
    path = reference(parent);
    terms = through_vector(e.joint);
    terms.push_back(travel(e.joint));
    for (const Term& t : negated(body_vector(b, e.joint))) terms.push_back(t);
  } else {  // block -> guide
    path = position(parent, e.joint);
    terms = negated(std::vector<Term>{travel(e.joint)});
    for (const Term& t : negated(through_vector(e.joint))) terms.push_back(t);
  }
  // The last step of position() is the parent's vector to the joint: same tree edge.
  std::vector<Term> step = path.steps.empty() || path.steps.back().first != -1 ? std::vector<Term>{} : path.steps.back().second;
  if (!path.steps.empty() && path.steps.back().first == -1) path.steps.pop_back();
  for (const Term& t : terms) step.push_back(t);
  path.steps.push_back({body.parent_edge, step});
  return path;
}

std::vector<Term> LinkageWriter::flatten(const Path& path, std::size_t from) {
  std::vector<Term> terms;
  for (std::size_t k = from; k < path.steps.size(); ++k)
    for (const Term& t : path.steps[k].second) terms.push_back(t);
  return terms;
}

std::string LinkageWriter::cycle_name(const Path& a, const Path& b, std::size_t common, std::size_t closing) const {
  std::vector<std::string> names;
  for (std::size_t k = common; k < a.steps.size(); ++k)
    if (a.steps[k].first >= 0) names.push_back(linkage_.joints[edges_[std::size_t(a.steps[k].first)].joint].name);
  names.push_back(linkage_.joints[closing].name);
  for (std::size_t k = b.steps.size(); k-- > common;)
    if (b.steps[k].first >= 0) names.push_back(linkage_.joints[edges_[std::size_t(b.steps[k].first)].joint].name);
  // Letters run together as the textbooks write a loop (ABCD); a joint named with more
  // than a letter (B2, F5) would make the run one unreadable symbol (AB2BC), so then
  // the joints are parted by '_' (A_B2_B_C), the one separator a loop name may hold.
  const bool letters = std::all_of(names.begin(), names.end(), [](const std::string& n) { return n.size() == 1; });
  std::string name;
  for (const std::string& n : names) name += (name.empty() || letters ? "" : "_") + n;
  return name;
}

void LinkageWriter::write_loops() {
  std::set<std::string> loop_names;
  for (const Edge& e : edges_) {
    if (e.in_tree) continue;
    Path a, b;
    std::vector<Term> extra;
    if (!e.slider) {
      a = position(e.a, e.joint);
      b = position(e.b, e.joint);
    } else {  // block's joint = guide's through point + travel
      a = position(e.b, e.joint);
      b = reference(e.a);
      std::vector<Term> along = through_vector(e.joint);
      along.push_back(travel(e.joint));
      b.steps.push_back({-1, along});
    }
    std::size_t common = 0;
    while (common < a.steps.size() && common < b.steps.size() && a.steps[common].first >= 0 &&
           a.steps[common].first == b.steps[common].first)
      ++common;
    // A walk round the loop: out along a to the closing joint, back along b (its terms
    // in reverse order, negated), so that every partial sum is a joint (course notes
    // read the loop so, and its polygon's vertices are the joints).
    std::vector<Term> terms = flatten(a, common);
    const std::vector<Term> back = negated(flatten(b, common));
    terms.insert(terms.end(), back.rbegin(), back.rend());
    TermSum loop{cycle_name(a, b, common, e.joint), linkage_.joints[e.joint].where, terms};
    while (!loop_names.insert(loop.name).second) loop.name += "_";
    loops_.push_back(loop);
  }
}

void LinkageWriter::write_points() {
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
    const Joint& joint = linkage_.joints[j];
    if (joint.ground) {
      ground_.push_back({joint.name, joint.where, flatten(position(0, j), 0)});
      continue;
    }
    // From the body nearest ground: the shortest sum (a slider's point from its guide).
    std::size_t body = 0;
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
      const bool on = std::find(bodies_[b].joints.begin(), bodies_[b].joints.end(), j) != bodies_[b].joints.end() &&
                      !(joint.kind == Joint::Kind::slider && bodies_[b].name == joint.guide);
      if (on && (body == 0 || bodies_[b].depth < bodies_[body].depth)) body = b;
    }
    // A slider where a pin of its block is: the pin names the point.
    bool shown = false;
    if (joint.kind == Joint::Kind::slider) {
      for (std::size_t k : bodies_[body].joints)
        shown = shown || (k != j && linkage_.joints[k].kind == Joint::Kind::pin && std::abs(at_[k] - at_[j]) < 1e-12);
    }
    if (shown) continue;
    points_.push_back({joint.name, joint.where, flatten(position(body, j), 0), true});
  }
  for (const LinkPoint& p : linkage_.points) {
    const auto it = body_index_.find(p.link);
    if (it == body_index_.end() || it->second == 0) {
      fail(p.where, "point \"" + p.name + "\" is on link \"" + p.link + "\", which is not a link of [links]");
    }
    const Body& body = bodies_[it->second];
    const Point2 at(value_of(p.x, Dimension::length, p.where, "point " + p.name + " x"),
                    value_of(p.y, Dimension::length, p.where, "point " + p.name + " y"));
    std::vector<Term> terms = flatten(reference(it->second), 0);
    const Point2 v = at - at_[body.joints[0]];
    if (std::abs(v) > 1e-12 * (1 + std::abs(at))) {
      std::set<std::string> follows = body_follows(body);
      for (const std::string* text : {&p.x, &p.y}) {
        const std::set<std::string> more = text_follows(*text);
        follows.insert(more.begin(), more.end());
      }
      const std::string factor = add_parameter("r_" + body.name + "_" + p.name, std::abs(v), Dimension::length, p.where, follows);
      terms.push_back(rotated({factor}, body.angle, wrapped(std::arg(v) - body.angle0 + body.offset),
                              "beta_" + body.name + "_" + p.name, p.where, "", follows));
    }
    points_.push_back({p.name, p.where, terms});
  }
}

}  // namespace kinema::linkage_detail
