// Everything a view shows beyond the solved table, computed once, before any printer
// runs: design figures (Grashof, transmission angle, toggles, limits, time ratio), the
// dyad-by-dyad derivation, a spatial chain worked out at the instant, and per printed
// value the drawing's geometry, the velocity and acceleration polygons and the instant
// centres. A printer receives the model, the results and this, and only formats
// (cmake/stage_order.cmake refuses a printer that includes a solving header).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/analysis/chain_instant.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/analysis/instant_centres.hpp"
#include "engine/analysis/motion_drawing.hpp"
#include "engine/analysis/polygons.hpp"
#include "engine/analysis/resolving.hpp"
#include "engine/model.hpp"
#include "engine/symbolic/dyad_derivation_types.hpp"

namespace kinema {

/// What a view shows beyond the table (Printer::needs says it for a print job), and so
/// what analyse_for_views computes: nothing more.
struct ViewNeeds {
  bool design_figures = false;   ///< A four-bar's figures and crank-driven sliders' strokes (a turn solved, toggles, limits).
  bool dyad_derivation = false;  ///< The relations dyad by dyad in `method` (when it is not the loops').
  bool chain_at_instant = false; ///< A driven spatial chain worked out at the instant in `basis`.
  bool drawings = false;         ///< Per printed value: drawing geometry, polygons, instant centres.
  /// Every row moving (the web page): the drawing's geometry of the whole table, and per
  /// row the polygons and instant centres (ValueAnalysis without its one-value geometry).
  bool motion = false;
  /// With motion: the dimension sliders' ranges over the rows (engine/analysis/slider_ranges).
  bool slider_ranges = false;
  DerivationMethod method = DerivationMethod::loops;
  std::string basis;  ///< The frame a chain's vectors are given along (empty: the observer's).
};

/// What the drawings and figures of one printed value show. Empty for a value that is
/// not assembled (a document draws nothing there).
struct ValueAnalysis {
  /// A joints-and-links mechanism placed in closed form, as its bodies; otherwise a
  /// vector-loop file's terms as segments and the named points on its links.
  std::optional<LinkageDrawing> linkage;
  std::vector<DrawingSegment> segments;
  std::vector<PointOnLink> points_on_links;
  std::vector<LetteredCorner> lettered_corners;
  std::vector<DrawnDimension> dimensions;
  /// A spatial chain: its frames where the value puts them.
  std::vector<PlacedFrame> frames;
  /// Velocity and acceleration polygons (a planar mechanism at an ok value).
  std::optional<std::pair<Polygon, Polygon>> polygons;
  /// Instant centres (joints and links placed in closed form, at an ok value).
  std::optional<InstantCentres> centres;
};

struct Analysis {
  std::optional<FourBarFigures> four_bar;
  std::vector<Strokes> strokes;
  std::optional<DyadDerivation> dyads;
  std::optional<ChainAtInstant> chain;
  /// A vector-loop file's link numbers, as DrawingSegment::link and PointOnLink::link index them.
  std::vector<std::string> link_labels;
  /// Per row of the printed values, in order (when drawings or motion are asked for).
  std::vector<ValueAnalysis> values;
  /// The drawing's geometry at every row (when motion is asked for).
  std::optional<MotionDrawing> motion;
  /// What solving again for other dimensions needs (when motion is asked for and the
  /// model can be: engine/analysis/resolving.hpp).
  std::optional<Resolving> resolving;
};

/// Computes what `needs` asks of the model at `values` (the printed values; nullptr when
/// a view prints none), once. A plot's sweep needs no analysis of its own: it is the
/// solved table, drawn. InputError for a basis that is not a frame of the chain, and for
/// a dyad method on a file that is not joints and links solved dyad by dyad.
Analysis analyse_for_views(const Model& model, const MotionTable* values, const ViewNeeds& needs);

}  // namespace kinema
