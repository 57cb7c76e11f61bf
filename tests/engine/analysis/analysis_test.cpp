// The analysis evaluates what the model derived and compiled (issue 34: one chain rule,
// one builder of relative-motion and Coriolis terms, one tape input order): drawing
// geometry, polygons, a chain's placed frames and the moving drawing take no derivative
// and compile no tape of their own. The engine's counts of both are read around them.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>

#include "engine/analysis/analysis.hpp"
#include "engine/analysis/motion_drawing.hpp"
#include "engine/base/work_count.hpp"
#include "tests/test_support.hpp"

namespace {

using kinema::Work;

struct DerivingWork {
  std::uint64_t compiled = kinema::work_done_in_process(Work::tape_compile);
  std::uint64_t differentiated = kinema::work_done_in_process(Work::differentiation);
};

// The values a sample's documents print, and one more.
kinema::MotionTable printed_values(const kinema::Model& model) {
  std::vector<double> inputs = model.system.input.values;
  if (inputs.empty()) inputs = {0.3};
  inputs.push_back(inputs.back() + 0.1);
  return kinema::solve_motion(model, inputs);
}

}  // namespace

TEST_CASE("engine/analysis: drawings, polygons and placed frames take no derivative and compile no tape") {
  int drawn = 0, polygons = 0;
  for (const char* name : kinema_test::kSamples) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::MotionTable values = printed_values(model);
    const DerivingWork before;
    const kinema::MechanismGeometry geometry(model);
    const kinema::PolygonBuilder builder(model);
    for (const kinema::MotionState& s : values) {
      drawn += !geometry.segments(s).empty();
      geometry.points_on_links(s);
      polygons += builder.polygons(s).has_value();
      kinema::placed_frames(model, s);
    }
    kinema::motion_drawing(model, values);
    const DerivingWork after;
    CHECK(after.compiled == before.compiled);
    CHECK(after.differentiated == before.differentiated);
  }
  CHECK(drawn > 0);  // the loop drew and polygons were found: the counts were read around real work
  CHECK(polygons > 0);
}

TEST_CASE("engine/analysis: analyse_for_views with drawings takes no derivative and compiles no tape") {
  // Every sample: joints and links, vector loops (whose instant centres read their links'
  // rates off the model's tape) and spatial chains (frames placed).
  kinema::ViewNeeds needs;
  needs.drawings = true;
  int vector_loop_centres = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    CAPTURE(std::string(name));
    const kinema::MotionTable values = printed_values(model);
    const DerivingWork before;
    const kinema::Analysis analysis = kinema::analyse_for_views(model, &values, needs);
    const DerivingWork after;
    CHECK(after.compiled == before.compiled);
    CHECK(after.differentiated == before.differentiated);
    REQUIRE(analysis.values.size() == values.size());
    const bool vector_loops = !model.system.plan && model.system.frames.empty();
    for (const kinema::ValueAnalysis& value : analysis.values) vector_loop_centres += vector_loops && value.centres;
  }
  // The centres of vector-loop files were found, so the counts were read around them.
  CHECK(vector_loop_centres >= 6);
}
