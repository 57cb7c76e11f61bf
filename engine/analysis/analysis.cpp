#include "engine/analysis/analysis.hpp"

#include "engine/symbolic/dyad_method.hpp"

namespace kinema {
namespace {

// The drawings and figures of the printed values: the geometry and the polygons read the
// model's link vectors, derived and compiled with it (nothing is derived or compiled here).
// Without `one_value_geometry` (a view of every row, which has the drawing's geometry of
// the whole motion) only the polygons and the instant centres.
std::vector<ValueAnalysis> analyse_values(const Model& model, const MotionTable& values,
                                          std::vector<std::string>& link_labels, bool one_value_geometry) {
  const ConstraintSystem& system = model.system;
  std::vector<ValueAnalysis> analysed(values.size());
  if (!system.frames.empty()) {  // a spatial chain: its frames placed
    for (std::size_t row = 0; one_value_geometry && row < values.size(); ++row) {
      const MotionState s = values[row];
      if (s.status != Status::unassembled) analysed[row].frames = placed_frames(model, s);
    }
    return analysed;
  }
  const MechanismGeometry geometry(model);
  const PolygonBuilder polygons(model);
  link_labels = geometry.link_labels();
  for (std::size_t row = 0; row < values.size(); ++row) {
    const MotionState s = values[row];
    if (s.status == Status::unassembled) continue;
    ValueAnalysis& value = analysed[row];
    if (one_value_geometry) value.linkage = linkage_drawing(system, s);
    if (one_value_geometry && !value.linkage) {
      value.segments = geometry.segments(s);
      value.points_on_links = geometry.points_on_links(s);
      value.lettered_corners = geometry.lettered_corners(s, value.segments);
      value.dimensions = geometry.dimensions(value.segments);
    }
    value.polygons = polygons.polygons(s);
    value.centres = instant_centres(geometry, s);
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
    analysis.values = analyse_values(model, *values, analysis.link_labels, needs.drawings);
  if (needs.motion && values) analysis.motion = motion_drawing(model, *values);
  if (needs.motion) analysis.resolving = resolving(model, needs.slider_ranges ? values : nullptr);
  return analysis;
}

}  // namespace kinema
