// The drawing's geometry at every row of a solved table, for views that show the
// mechanism moving (the web page): what the worked solution draws at one value
// (engine/analysis/geometry.hpp), with the parts that do not change from row to row
// given once and the coordinates that do given a row at a time.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "engine/analysis/geometry.hpp"

namespace kinema {

struct MotionDrawing {
  /// linkage: joints and links placed in closed form (linkage_drawing); loops: the loops'
  /// terms (MechanismGeometry::segments); chain: a spatial chain's frames (placed_frames).
  enum class Form { none, linkage, loops, chain };
  Form form = Form::none;

  // Form::linkage. Each row: x, y of every joint (SI), then the angle (rad) of each block.
  struct Link {
    std::string name;
    std::vector<std::size_t> joints;  ///< Indices into joint_names.
    bool block = false;
  };
  std::vector<std::string> joint_names;
  std::vector<Link> links;
  std::vector<std::size_t> ground_pivots;      ///< Indices into joint_names.
  std::vector<LinkageDrawing::Guide> guides;   ///< Fixed guides (SI).

  // Form::loops. Each row: for each segment from, to, block, along (x, y each: 8 values),
  // then for each point on a link from, at (4 values). The kinds, links, guides and
  // labels below are the first drawn row's (the terms are the same at every row).
  std::vector<DrawingSegment> segments;
  std::vector<PointOnLink> points_on_links;
  std::vector<std::string> link_labels;
  std::vector<LetteredCorner> lettered_corners;  ///< At the segments' ends they name (every row).

  // Form::chain. Each row: for each frame its origin (x, y, z), then its x, y and z axes
  // (unit vectors, observer basis): 12 values a frame.
  std::vector<std::string> frame_names, frame_parents;
  ChainBodies bodies;
  ChainView view;  ///< Chosen at the first drawn row (chain_view), the one a page opens at.

  /// One entry a table row: the coordinates above (SI), empty where the row has no
  /// position (unassembled); NaN where a part is not known at that row (points on links
  /// of a singular row).
  std::vector<std::vector<double>> rows;
};

/// The geometry of every row of `table`, solved for `model` (nothing is solved here:
/// the positions are the table's; joints and links are placed from them in closed form).
MotionDrawing motion_drawing(const Model& model, const MotionTable& table);

}  // namespace kinema
