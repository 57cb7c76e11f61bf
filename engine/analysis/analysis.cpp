#include "engine/analysis/analysis.hpp"

#include "engine/symbolic/dyad_method.hpp"

namespace kinema {
namespace {

// The drawings and figures of the printed values, each built once for the run: the
// geometry's and the polygons' tapes are compiled here, not per value or per printer.
std::vector<ValueAnalysis> analyse_values(const ConstraintSystem& system, const MotionTable& values,
                                          std::vector<std::string>& link_labels, bool one_value_geometry) {
  std::vector<ValueAnalysis> analysed(values.size());
  if (!system.frames.empty()) {  // a spatial chain: its frames placed
    for (std::size_t row = 0; one_value_geometry && row < values.size(); ++row) {
      const MotionState s = values[row];
      if (s.status != Status::unassembled) analysed[row].frames = placed_frames(system, s);
    }
    return analysed;
  }
  const MechanismGeometry geometry(system);
  const PolygonBuilder polygons(system);
  link_labels = geometry.link_labels();
  for (std::size_t row = 0; row < values.size(); ++row) {
    const MotionState s = values[row];
    if (s.status == Status::unassembled) continue;
    ValueAnalysis& value = analysed[row];
    if (one_value_geometry) value.linkage = linkage_drawing(system, s);
    if (one_value_geometry && !value.linkage) {
      value.segments = geometry.segments(s);
      value.points_on_links = geometry.points_on_links(s);
    }
    value.polygons = polygons.polygons(s);
    value.centres = instant_centres(system, s);
  }
  return analysed;
}

}  // namespace

Analysis analyse_for_views(const Model& model, const MotionTable* values, const ViewNeeds& needs) {
  const ConstraintSystem& system = model.system;
  Analysis analysis;
  if (needs.design_figures) {
    analysis.four_bar = four_bar_figures(model);
    analysis.strokes = slider_strokes(model);
  }
  if (needs.dyad_derivation && needs.method != DerivationMethod::loops)
    analysis.dyads = derive_by_dyads(system, needs.method);
  if (needs.chain_at_instant && is_driven_chain(system)) analysis.chain = chain_at_instant(system, needs.basis);
  if ((needs.drawings || needs.motion) && values)
    analysis.values = analyse_values(system, *values, analysis.link_labels, needs.drawings);
  if (needs.motion && values) analysis.motion = motion_drawing(system, *values);
  return analysis;
}

}  // namespace kinema
