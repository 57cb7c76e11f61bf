#include "engine/analysis/structure.hpp"

namespace kinema {
namespace {

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

}  // namespace

std::string mobility_text(const Linkage& linkage) {
  const int n = linkage.body_count, j = linkage.joint_count;
  return "3(n - 1) - 2j = 3*" + std::to_string(n - 1) + " - 2*" + std::to_string(j) + " = " +
         std::to_string(3 * (n - 1) - 2 * j) + " (n = " + std::to_string(n) + " bodies with ground, j = " +
         std::to_string(j) + " joints)";
}

std::vector<std::string> structure_lines(const Linkage& linkage) {
  std::vector<std::string> lines;
  std::size_t dyads = 0;
  for (const StructureGroup& group : linkage.structure) {
    if (group.kind == "driver") {
      lines.push_back("driver: link " + group.links.at(0) + (group.joints.empty() ? "" : " (" + joined(group.joints) + ")"));
    } else if (group.kind == "group") {
      lines.push_back("not a dyad: links " + joined(group.links) + ", solved together by Newton on their loops");
    } else {
      lines.push_back("dyad " + std::to_string(++dyads) + ", " + group.kind + ": links " + joined(group.links) +
                      "; joints " + joined(group.joints) +
                      (group.assembly.empty() ? "" : "; assembly " + group.assembly + " (stated in the file)"));
    }
  }
  return lines;
}

std::string describe_dyad(const Linkage& linkage, std::size_t k) {
  std::size_t dyads = 0;
  for (const StructureGroup& group : linkage.structure) {
    if (group.kind == "driver" || group.kind == "group") continue;
    if (dyads++ == k) {
      return "dyad " + std::to_string(k + 1) + " (" + group.kind + ": links " + joined(group.links) + "; joints " +
             joined(group.joints) + ")";
    }
  }
  return "dyad " + std::to_string(k + 1);
}

}  // namespace kinema
