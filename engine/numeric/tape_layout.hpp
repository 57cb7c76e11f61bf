// Where everything sits in the compiled tape of a constraint system, said
// once: the input registers, the stages and their outputs, the input levels.
// The workspaces, the batch workspace and the C++ exporter all read this.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/symbolic/centre_body.hpp"

namespace kinema {

struct TapeLayout {
  std::size_t parameter_count = 0;
  std::size_t unknown_count = 0;
  std::vector<std::size_t> point_dimensions;  ///< 2 or 3 per point.
  std::size_t frame_count = 0;                ///< Frames of a spatial chain (angular velocity and acceleration).
  std::size_t link_vector_count = 0;          ///< A planar system's link vectors (Derivation::link_vectors).
  // Joints and links (SolvingPlan), on the drawing stage: 0 for anything else.
  std::size_t linkage_joint_count = 0;   ///< SolvingPlan::joints.
  std::size_t linkage_block_count = 0;   ///< Bodies that are slider blocks.
  std::size_t linkage_guide_count = 0;   ///< Sliders on a fixed guide (guide 0).
  std::size_t linkage_column_count = 0;  ///< The joints-and-links result columns (linkage_columns_begin on).
  /// A planar file's bodies whose instant centres the drawing stage holds (ground, body 0,
  /// is not listed: body b >= 1 is centre_bodies[b - 1]); empty for anything else.
  std::vector<CentreBody> centre_bodies;

  // Input registers: [parameters, theta, thetad, thetadd, q, qd, qdd].
  std::size_t parameter(std::size_t p) const { return p; }
  std::size_t input() const { return parameter_count; }
  std::size_t rate() const { return parameter_count + 1; }
  std::size_t second_rate() const { return parameter_count + 2; }
  std::size_t q(std::size_t i) const { return parameter_count + 3 + i; }
  std::size_t qd(std::size_t i) const { return parameter_count + 3 + unknown_count + i; }
  std::size_t qdd(std::size_t i) const { return parameter_count + 3 + 2 * unknown_count + i; }
  std::size_t input_register_count() const { return parameter_count + 3 + 3 * unknown_count; }

  // Stages, run in this order: each may use what the earlier ones computed.
  static constexpr std::size_t kPositionStage = 0;      ///< Phi, Phi_q (column-major), Phi_theta.
  static constexpr std::size_t kAccelerationStage = 1;  ///< gamma.
  /// Each point: position, velocity, acceleration; then each frame: angular velocity and
  /// angular acceleration (3 + 3, observer basis).
  static constexpr std::size_t kPointStage = 2;
  /// What the drawings and polygons show, run only for a printed value: each link vector,
  /// then each frame's placement. It reads the earlier stages' registers but changes none
  /// of their instructions (the solvers and the exported code are the same without it).
  static constexpr std::size_t kDrawingStage = 3;
  static constexpr std::size_t kStageCount = 4;

  // Outputs of the position stage.
  std::size_t phi(std::size_t i) const { return i; }
  std::size_t phi_q(std::size_t i, std::size_t j) const { return unknown_count + j * unknown_count + i; }
  std::size_t phi_theta(std::size_t i) const { return unknown_count + unknown_count * unknown_count + i; }
  std::size_t position_output_count() const { return unknown_count * (unknown_count + 2); }

  // Outputs of the point stage: point p's components of position, then of
  // velocity, then of acceleration (3 * dimension values).
  std::size_t point_output(std::size_t p) const {
    std::size_t offset = 0;
    for (std::size_t k = 0; k < p; ++k) offset += 3 * point_dimensions[k];
    return offset;
  }
  std::size_t point_output_count() const { return point_output(point_dimensions.size()); }
  std::size_t frame_output(std::size_t f) const { return point_output_count() + 6 * f; }
  /// Everything the point stage computes: points, then frames.
  std::size_t observable_output_count() const { return frame_output(frame_count); }

  // Outputs of the drawing stage: link vector k's x, y; its parts' x, y in the order of
  // LinkVectorPart; its parts' lengths as derived; its guide's x, y (0 for none); its
  // angle's rate, real and imaginary parts (0 for a vector not polar). Then frame f's
  // origin (x, y, z) and its rotation (row-major, observer basis).
  static constexpr std::size_t kVectorPartCount = 6;
  static constexpr std::size_t kVectorPositionAt = 0, kVectorPartsAt = 2, kVectorMagnitudesAt = 2 + 2 * kVectorPartCount,
                               kVectorGuideAt = kVectorMagnitudesAt + kVectorPartCount,
                               kVectorAngleRateAt = kVectorGuideAt + 2, kVectorOutputs = kVectorAngleRateAt + 2,
                               kFramePlacementOutputs = 12;
  std::size_t link_vector_output(std::size_t k) const { return kVectorOutputs * k; }
  std::size_t frame_placement_output(std::size_t f) const {
    return link_vector_output(link_vector_count) + kFramePlacementOutputs * f;
  }
  /// Then, for joints and links: each joint's x, y (SolvingPlan::joints order); each block's
  /// angle (body order); each fixed guide's point where its coordinate is 0 and its unit
  /// direction (x, y each, SolvingPlan::sliders order); then the joints-and-links result
  /// columns in SI (angles in rad, not wrapped), as result_columns lists them.
  std::size_t linkage_joint_output(std::size_t j) const { return frame_placement_output(frame_count) + 2 * j; }
  std::size_t linkage_block_output(std::size_t b) const { return linkage_joint_output(linkage_joint_count) + b; }
  std::size_t linkage_guide_output(std::size_t g) const { return linkage_block_output(linkage_block_count) + 4 * g; }
  std::size_t linkage_column_output(std::size_t c) const { return linkage_guide_output(linkage_guide_count) + c; }
  /// Then, for a planar file's instant centres (engine/symbolic/centre_formulas.hpp):
  /// per body b >= 1 its angular velocity and a point on it (x, y); then per pair a < b of
  /// bodies (ground, 0, included; in that order) N = c_b - c_a (x, y) and D = omega_a -
  /// omega_b, where c = v_P - i omega P is the body's velocity at the origin. Their centre
  /// is N / (i D), or at infinity across N where they turn alike.
  static constexpr std::size_t kCentreBodyOutputs = 3, kCentrePairOutputs = 3;
  std::size_t centre_body_output(std::size_t b) const {
    return linkage_column_output(linkage_column_count) + kCentreBodyOutputs * (b - 1);
  }
  std::size_t centre_pair_output(std::size_t a, std::size_t b) const {
    const std::size_t n = centre_bodies.size() + 1;
    std::size_t before = 0;  // pairs before (a, b) in the order a < b
    for (std::size_t i = 0; i < a; ++i) before += n - 1 - i;
    return centre_body_output(n) + kCentrePairOutputs * (before + b - a - 1);
  }
  std::size_t drawing_output_count() const {
    const std::size_t n = centre_bodies.size() + 1;
    return centre_body_output(n) + kCentrePairOutputs * (n * (n - 1) / 2);
  }

  // Input levels (how often an input changes): work on level-0 inputs runs once,
  // on the input and its rates once per value, on q once per Newton iterate.
  static constexpr int kParameterLevel = 0, kInputLevel = 1, kCoordinateLevel = 2, kRateLevel = 3,
                       kSecondRateLevel = 4;
  std::vector<int> input_levels() const {
    std::vector<int> levels(input_register_count(), kParameterLevel);
    for (std::size_t r = input(); r < q(0); ++r) levels[r] = kInputLevel;
    for (std::size_t i = 0; i < unknown_count; ++i) {
      levels[q(i)] = kCoordinateLevel;
      levels[qd(i)] = kRateLevel;
      levels[qdd(i)] = kSecondRateLevel;
    }
    return levels;
  }
};

}  // namespace kinema
