// The solving order: the driver, then dyads (two links joined to what is known by two
// outer joints), links that form none left to Newton.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

// The driver, then dyads in solving order: two links not yet placed that share one
// joint and each have one joint to what is placed. Links left over form no dyad.
void LinkageWriter::decompose() {
  plan_.body_count = static_cast<int>(bodies_.size());
  plan_.joint_count = static_cast<int>(edges_.size());
  std::vector<int> known(bodies_.size(), -1);  // step at which the body became known
  known[0] = 0;
  SolvingPlan::Step driver;
  driver.kind = "driver";
  std::size_t driver_body = driver_body_;
  if (driver_slider_ >= 0) {
    for (const Edge& e : edges_)
      if (e.slider && static_cast<int>(e.joint) == driver_slider_) driver_body = e.b;
    driver.joints.push_back(linkage_.joints[std::size_t(driver_slider_)].name);
  } else {
    for (const Edge& e : edges_)
      if (!e.slider && e.a == 0 && e.b == driver_body && driver.joints.empty()) driver.joints.push_back(linkage_.joints[e.joint].name);
  }
  driver.links.push_back(bodies_[driver_body].name);
  known[driver_body] = 1;
  plan_.steps.push_back(driver);
  const auto letter = [](const Edge& e) { return e.slider ? "T" : "R"; };
  for (int step = 2;; ++step) {
    bool found = false;
    // One pass over the joints: each unplaced link's joints to what is placed, and the
    // joints between two unplaced links; then the first pair (in link order) that is a dyad.
    std::vector<int> to_known(bodies_.size(), 0), known_edge(bodies_.size(), -1);
    std::map<std::pair<std::size_t, std::size_t>, std::pair<int, int>> between;  // count, edge
    for (std::size_t k = 0; k < edges_.size(); ++k) {
      const std::size_t a = edges_[k].a, b = edges_[k].b;
      if (known[a] >= 0 && known[b] < 0) {
        ++to_known[b];
        known_edge[b] = static_cast<int>(k);
      } else if (known[b] >= 0 && known[a] < 0) {
        ++to_known[a];
        known_edge[a] = static_cast<int>(k);
      } else if (known[a] < 0 && known[b] < 0) {
        auto& [count, edge] = between[{std::min(a, b), std::max(a, b)}];
        ++count;
        edge = static_cast<int>(k);
      }
    }
    for (const auto& [pair, link] : between) {
      const auto [l1, l2] = pair;
      if (link.first != 1 || to_known[l1] != 1 || to_known[l2] != 1) continue;
      int outer1 = known_edge[l1], outer2 = known_edge[l2];
      const int inner = link.second;
      // Read from the side of the body placed last (the moving one), pins first on a tie.
      const auto other = [&](int k, std::size_t b) {
        const Edge& e = edges_[std::size_t(k)];
        return e.a == b ? e.b : e.a;
      };
      std::size_t first = l1, second = l2;
      const int k1 = known[other(outer1, l1)], k2 = known[other(outer2, l2)];
      if (k2 > k1 || (k2 == k1 && edges_[std::size_t(outer1)].slider && !edges_[std::size_t(outer2)].slider)) {
        std::swap(first, second);
        std::swap(outer1, outer2);
      }
      SolvingPlan::Step dyad;
      dyad.kind = std::string(letter(edges_[std::size_t(outer1)])) + letter(edges_[std::size_t(inner)]) +
                  letter(edges_[std::size_t(outer2)]);
      dyad.links = {bodies_[first].name, bodies_[second].name};
      dyad.joints = {linkage_.joints[edges_[std::size_t(outer1)].joint].name,
                     linkage_.joints[edges_[std::size_t(inner)].joint].name,
                     linkage_.joints[edges_[std::size_t(outer2)].joint].name};
      plan_.steps.push_back(dyad);
      dyad_edges_.push_back({first, second, std::size_t(outer1), std::size_t(inner), std::size_t(outer2)});
      known[l1] = known[l2] = step;
      found = true;
      break;
    }
    if (!found) break;
  }
  SolvingPlan::Step rest;
  rest.kind = "group";
  for (std::size_t b = 1; b < bodies_.size(); ++b)
    if (known[b] < 0) rest.links.push_back(bodies_[b].name);
  if (!rest.links.empty()) plan_.steps.push_back(rest);
}

}  // namespace kinema::linkage_detail
