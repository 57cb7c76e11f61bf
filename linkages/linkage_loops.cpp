#include "linkages/linkage_loops.hpp"

#include <utility>

#include "linkages/linkage_writer.hpp"
#include "loops/planar_loops.hpp"
#include "readers/mechanism_file.hpp"  // check_shared_names

namespace kinema {

using linkage_detail::LinkageWriter;

LinkageLoops linkage_loops(const Mechanism& written) {
  LinkageLoops result{written, {}};
  LinkageWriter writer(result.loops);
  writer.write();
  result.plan = std::move(writer).plan();
  result.loops.linkage.reset();  // a vector-loop mechanism now: the front end's work is done
  return result;
}

ConstraintSystem build_linkage_system(const Mechanism& written) {
  LinkageLoops derived = linkage_loops(written);
  check_shared_names(derived.loops);
  ConstraintSystem system = build_planar_loops(derived.loops);
  system.plan = std::move(derived.plan);
  return system;
}

}  // namespace kinema
