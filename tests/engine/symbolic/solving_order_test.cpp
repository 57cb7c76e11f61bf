// engine/symbolic/solving_order: which unknowns each block of equation groups
// solves, from the groups' labels alone. Systems are built by hand (any
// equations will do: only which unknowns each group holds matters) and from
// the samples.
#include <doctest/doctest.h>

#include <set>
#include <vector>

#include "engine/symbolic/solving_order.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using GiNaC::ex;
using kinema::ConstraintSystem;
using kinema::SolvingBlock;
using V = std::vector<std::size_t>;

namespace {

// A system of `unknowns` coordinates and groups of equations, each equation
// given by the unknowns it holds (the equation is their sum times a parameter).
ConstraintSystem hand_built(std::size_t unknowns, const std::vector<std::vector<V>>& groups) {
  ConstraintSystem system;
  system.parameters.push_back({});
  system.parameters[0].symbol = GiNaC::realsymbol("k");
  system.input.symbol = GiNaC::realsymbol("t");
  for (std::size_t j = 0; j < unknowns; ++j) {
    kinema::Coordinate q;
    q.name = "q" + std::to_string(j);
    q.symbol = GiNaC::realsymbol(q.name);
    system.unknowns.push_back(q);
  }
  for (std::size_t k = 0; k < groups.size(); ++k) {
    kinema::EquationGroup group;
    group.kind = "loop";
    group.name = "G" + std::to_string(k);
    for (std::size_t e = 0; e < groups[k].size(); ++e) {
      ex expression = system.parameters[0].symbol * system.input.symbol;
      for (std::size_t j : groups[k][e]) expression += sin(system.unknowns[j].symbol);
      group.equations.push_back(system.equations.size());
      system.equations.push_back({expression, k, e == 0 ? "x" : "y"});
    }
    system.groups.push_back(group);
  }
  return system;
}

// Every unknown and every equation in exactly one block, each block square.
void check_partition(const ConstraintSystem& system, const std::vector<SolvingBlock>& blocks) {
  std::multiset<std::size_t> unknowns, equations, groups;
  for (const SolvingBlock& block : blocks) {
    CHECK(block.unknowns.size() == block.equations.size());
    unknowns.insert(block.unknowns.begin(), block.unknowns.end());
    equations.insert(block.equations.begin(), block.equations.end());
    groups.insert(block.groups.begin(), block.groups.end());
    // A block's equations are those of its groups.
    V expected;
    for (std::size_t k : block.groups)
      expected.insert(expected.end(), system.groups[k].equations.begin(), system.groups[k].equations.end());
    CHECK(block.equations == expected);
  }
  CHECK(unknowns.size() == system.unknowns.size());
  CHECK(std::set<std::size_t>(unknowns.begin(), unknowns.end()).size() == system.unknowns.size());
  CHECK(equations.size() == system.equations.size());
  CHECK(groups.size() == system.groups.size());
}

}  // namespace

TEST_CASE("engine/symbolic/solving_order: one loop is one block") {
  const ConstraintSystem system = kinema_unit::system_from_text(kinema_test::four_bar_text());
  const auto blocks = kinema::solving_order(system);
  REQUIRE(blocks.size() == 1);
  CHECK(blocks[0].groups == V{0});
  CHECK(blocks[0].equations == V{0, 1});
  CHECK(blocks[0].unknowns == V{0, 1});
}

TEST_CASE("engine/symbolic/solving_order: the samples' loops one after the other") {
  // Problem 3.22: loop O2AB closes theta3, r1; then O2ACD closes theta5, r6 (theta3 known).
  const ConstraintSystem sliders =
      kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("problem_3_22_six_bar_sliders.toml")));
  auto blocks = kinema::solving_order(sliders);
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].groups == V{0});
  CHECK(blocks[0].unknowns == V{0, 1});
  CHECK(blocks[1].groups == V{1});
  CHECK(blocks[1].equations == V{2, 3});
  CHECK(blocks[1].unknowns == V{2, 3});
  check_partition(sliders, blocks);

  // Problem 4.4: ABCD closes phi2, phi3; DEF then closes phi4 and yF although it holds phi3 too.
  const ConstraintSystem six =
      kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("problem_4_4_six_bar.toml")));
  blocks = kinema::solving_order(six);
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].unknowns == V{0, 1});
  CHECK(blocks[1].unknowns == V{2, 3});
  check_partition(six, blocks);
}

TEST_CASE("engine/symbolic/solving_order: a later group that can go first goes first") {
  // G0 holds all four unknowns; G1 only q2 and q3: G1 first, then G0 for q0 and q1.
  const ConstraintSystem system = hand_built(4, {{{0, 1, 2}, {1, 2, 3}}, {{2, 3}, {2}}});
  const auto blocks = kinema::solving_order(system);
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].groups == V{1});
  CHECK(blocks[0].equations == V{2, 3});
  CHECK(blocks[0].unknowns == V{2, 3});
  CHECK(blocks[1].groups == V{0});
  CHECK(blocks[1].unknowns == V{0, 1});
  check_partition(system, blocks);
}

TEST_CASE("engine/symbolic/solving_order: file order is kept where any order would do") {
  // Three independent loops: blocks in the order the groups were written.
  const ConstraintSystem system = hand_built(6, {{{4, 5}, {5}}, {{0}, {1, 0}}, {{2, 3}, {3}}});
  const auto blocks = kinema::solving_order(system);
  REQUIRE(blocks.size() == 3);
  CHECK(blocks[0].groups == V{0});
  CHECK(blocks[0].unknowns == V{4, 5});
  CHECK(blocks[1].groups == V{1});
  CHECK(blocks[1].unknowns == V{0, 1});
  CHECK(blocks[2].groups == V{2});
  CHECK(blocks[2].unknowns == V{2, 3});
  check_partition(system, blocks);
}

TEST_CASE("engine/symbolic/solving_order: once a group is solved, the earliest group it frees comes next") {
  // G0 needs G1's q2, q3; G2 is independent. G1 frees G0, and G0 comes before G2 as in the file.
  const ConstraintSystem system = hand_built(6, {{{0, 1, 2}, {3}}, {{2, 3}, {2}}, {{4, 5}, {5}}});
  const auto blocks = kinema::solving_order(system);
  REQUIRE(blocks.size() == 3);
  CHECK(blocks[0].groups == V{1});
  CHECK(blocks[1].groups == V{0});
  CHECK(blocks[1].unknowns == V{0, 1});
  CHECK(blocks[2].groups == V{2});
  check_partition(system, blocks);
}

TEST_CASE("engine/symbolic/solving_order: coupled groups are solved together") {
  // G0 closes q0, q1; G1 and G2 share q3, q4 and each hold three new unknowns: one last block.
  const ConstraintSystem system = hand_built(6, {{{0, 1}, {0}}, {{2, 3}, {4, 0}}, {{3, 4, 5}, {5}}});
  const auto blocks = kinema::solving_order(system);
  REQUIRE(blocks.size() == 2);
  CHECK(blocks[0].groups == V{0});
  CHECK(blocks[0].unknowns == V{0, 1});
  CHECK(blocks[1].groups == V{1, 2});
  CHECK(blocks[1].equations == V{2, 3, 4, 5});
  CHECK(blocks[1].unknowns == V{2, 3, 4, 5});
  check_partition(system, blocks);

  // Nothing separable at all: one block of everything.
  const ConstraintSystem knot = hand_built(4, {{{0, 1, 2}, {0}}, {{1, 2, 3}, {3}}});
  const auto one = kinema::solving_order(knot);
  REQUIRE(one.size() == 1);
  CHECK(one[0].groups == V{0, 1});
  CHECK(one[0].unknowns == V{0, 1, 2, 3});
  check_partition(knot, one);
}
