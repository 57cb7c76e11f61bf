#include "linkages/linkage_loops.hpp"

#include <utility>

#include "linkages/linkage_writer.hpp"
#include "loops/planar_system.hpp"
#include "readers/mechanism_file.hpp"  // check_shared_names

namespace kinema {
namespace {

using linkage_detail::LinkageTerms;
using linkage_detail::LinkageWriter;
using linkage_detail::TermSum;

// The file's declarations completed (parameters the loops need, input, unknowns), and
// its loops and points as terms.
std::pair<Mechanism, LinkageTerms> derive(const Mechanism& written) {
  Mechanism declared = written;
  LinkageWriter writer(declared);
  writer.write();
  LinkageTerms terms = std::move(writer).terms();
  declared.linkage.reset();  // a vector-loop mechanism now: the front end's work is done
  return {std::move(declared), std::move(terms)};
}

}  // namespace

LinkageLoops linkage_loops(const Mechanism& written) {
  auto [loops, terms] = derive(written);
  for (const TermSum& sum : terms.loops) {
    Loop loop;
    loop.name = sum.name;
    loop.complex_formula = linkage_detail::sum_text(sum.terms);
    loop.where = sum.where;
    loops.loops.push_back(loop);
  }
  for (const TermSum& sum : terms.points) loops.points.push_back({sum.name, linkage_detail::sum_text(sum.terms), sum.where, sum.is_joint});
  return {std::move(loops), std::move(terms.plan)};
}

ConstraintSystem build_linkage_system(const Mechanism& written) {
  auto [declared, terms] = derive(written);
  check_shared_names(declared);
  PlanarSystemBuilder builder(declared);
  for (const TermSum& loop : terms.loops) builder.add_loop(linkage_detail::planar_vector(loop, builder.formulas(), "loop"));
  builder.end_loops();
  for (const TermSum& point : terms.points) builder.add_point(linkage_detail::planar_vector(point, builder.formulas(), "point"));
  std::vector<std::pair<std::string, GiNaC::ex>> ground;
  for (const TermSum& joint : terms.ground)
    ground.emplace_back(joint.name, joint.terms.empty() ? GiNaC::ex(0)
                                                        : linkage_detail::planar_vector(joint, builder.formulas(), "point").vector);
  ConstraintSystem system = std::move(builder).system();
  system.ground_joints = std::move(ground);
  system.plan = std::move(terms.plan);
  return system;
}

}  // namespace kinema
