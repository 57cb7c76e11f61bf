#include "engine/analysis/motion_drawing.hpp"

#include <cmath>
#include <optional>

namespace kinema {

namespace {

void put(std::vector<double>& row, std::complex<double> z) {
  row.push_back(z.real());
  row.push_back(z.imag());
}

// Joints and links: the structure from the first row that places, then each row's joints
// by name (a joint a row does not place is NaN) and its blocks' angles.
void linkage_rows(const ConstraintSystem& system, const MotionTable& table, MotionDrawing& drawing) {
  for (std::size_t r = 0; r < table.size(); ++r) {
    const std::optional<LinkageDrawing> placed = linkage_drawing(system, table[r]);
    if (!placed) {
      drawing.rows.emplace_back();
      continue;
    }
    if (drawing.joint_names.empty()) {
      const auto index = [&](const std::string& name) {
        for (std::size_t j = 0; j < drawing.joint_names.size(); ++j)
          if (drawing.joint_names[j] == name) return j;
        drawing.joint_names.push_back(name);
        return drawing.joint_names.size() - 1;
      };
      for (const auto& pivot : placed->ground_pivots) drawing.ground_pivots.push_back(index(pivot.name));
      for (const auto& link : placed->links) {
        MotionDrawing::Link l{link.name, {}, link.block};
        for (const auto& joint : link.joints) l.joints.push_back(index(joint.name));
        drawing.links.push_back(l);
      }
      drawing.guides = placed->guides;
    }
    std::vector<std::complex<double>> at(drawing.joint_names.size(), {NAN, NAN});
    const auto place = [&](const LinkageDrawing::Joint& joint) {
      for (std::size_t j = 0; j < drawing.joint_names.size(); ++j)
        if (drawing.joint_names[j] == joint.name) at[j] = joint.at;
    };
    // A slider's joint is where its block is (the block's pin), not the point of its guide's
    // body the sketch had there: blocks placed last, whatever order the file lists links in.
    for (const auto& pivot : placed->ground_pivots) place(pivot);
    for (const bool blocks : {false, true})
      for (const auto& link : placed->links)
        if (link.block == blocks)
          for (const auto& joint : link.joints) place(joint);
    std::vector<double> row;
    for (const auto& z : at) put(row, z);
    for (const auto& link : placed->links)
      if (link.block) row.push_back(link.angle);
    drawing.rows.push_back(std::move(row));
  }
}

void loop_rows(const Model& model, const MotionTable& table, MotionDrawing& drawing) {
  const MechanismGeometry geometry(model);
  drawing.link_labels = geometry.link_labels();
  for (std::size_t r = 0; r < table.size(); ++r) {
    if (table.status(r) == Status::unassembled) {
      drawing.rows.emplace_back();
      continue;
    }
    const MotionState state = table[r];
    const std::vector<DrawingSegment> segments = geometry.segments(state);
    // Points on links need the points, known only where the row is ok.
    const std::vector<PointOnLink> on_links =
        state.status == Status::ok ? geometry.points_on_links(state) : std::vector<PointOnLink>{};
    if (drawing.segments.empty()) drawing.segments = segments;
    if (drawing.points_on_links.empty()) drawing.points_on_links = on_links;
    if (state.status == Status::ok && drawing.lettered_corners.empty())
      drawing.lettered_corners = geometry.lettered_corners(state, segments);
    std::vector<double> row;
    for (const DrawingSegment& s : segments) {
      put(row, s.from);
      put(row, s.to);
      put(row, s.block);
      put(row, s.along);
    }
    for (std::size_t p = 0; p < drawing.points_on_links.size(); ++p) {
      const bool known = p < on_links.size();
      put(row, known ? on_links[p].from : std::complex<double>(NAN, NAN));
      put(row, known ? on_links[p].at : std::complex<double>(NAN, NAN));
    }
    drawing.rows.push_back(std::move(row));
  }
  // Rows drawn before the first ok row lack the points on links' room: padded.
  const std::size_t width = 8 * drawing.segments.size() + 4 * drawing.points_on_links.size();
  for (auto& row : drawing.rows)
    if (!row.empty()) row.resize(width, NAN);
}

// A spatial chain: each row's frames where it puts them (origin, then the x, y, z axes).
void chain_rows(const Model& model, const MotionTable& table, MotionDrawing& drawing) {
  for (const FrameObservable& frame : model.system.frames) {
    drawing.frame_names.push_back(frame.name);
    drawing.frame_parents.push_back(frame.parent);
  }
  drawing.bodies = chain_bodies(model.system);
  bool viewed = false;
  for (std::size_t r = 0; r < table.size(); ++r) {
    std::vector<double> row;
    if (table.status(r) != Status::unassembled) {
      const MotionState state = table[r];
      const std::vector<PlacedFrame> frames = placed_frames(model, state);
      for (const PlacedFrame& frame : frames) {
        row.insert(row.end(), frame.origin.begin(), frame.origin.end());
        for (const auto& axis : frame.axes) row.insert(row.end(), axis.begin(), axis.end());
      }
      if (!viewed && state.status == Status::ok) {
        std::vector<std::array<double, 3>> points;
        for (const PointMotion& p : state.points) points.push_back({p.position[0], p.position[1], p.position[2]});
        drawing.view = chain_view(model.system, frames, points);
        viewed = true;
      }
    }
    drawing.rows.push_back(std::move(row));
  }
}

}  // namespace

MotionDrawing motion_drawing(const Model& model, const MotionTable& table) {
  const ConstraintSystem& system = model.system;
  MotionDrawing drawing;
  if (!system.frames.empty()) {
    drawing.form = MotionDrawing::Form::chain;
    chain_rows(model, table, drawing);
    return drawing;
  }
  if (system.plan && system.plan->closed_form) {
    drawing.form = MotionDrawing::Form::linkage;
    linkage_rows(system, table, drawing);
  } else {
    drawing.form = MotionDrawing::Form::loops;
    loop_rows(model, table, drawing);
  }
  return drawing;
}

}  // namespace kinema
