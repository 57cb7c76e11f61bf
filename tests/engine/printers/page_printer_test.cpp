// kinema page's C++ half: the drawing's geometry at every row (engine/analysis/motion_drawing)
// and the page printer's escaping and policy (engine/printers/web/page). What the page does
// with them in a browser is tests/browser/page_test.js.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "engine/base/sha256.hpp"
#include "engine/model.hpp"
#include "engine/printers/web/page.hpp"
#include "engine/printers/web/page_constructions.hpp"
#include "engine/run/view.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/motion_drawing.hpp"
#include "engine/analysis/resolving.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

namespace {

std::vector<double> turn_in_degrees(double step) {
  std::vector<double> inputs;
  for (double d = 0; d < 360; d += step) inputs.push_back(d * M_PI / 180);
  return inputs;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

}  // namespace

TEST_CASE("engine/analysis/motion_drawing: joints where the table's points are at each assembled row, none where it does not assemble") {
  const kinema::Model model =
      kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"), kinema::DerivationScope::evaluation);
  const kinema::MotionTable table = kinema::solve_motion(model, turn_in_degrees(10));
  const kinema::MotionDrawing drawing = kinema::motion_drawing(model, table);
  REQUIRE(drawing.form == kinema::MotionDrawing::Form::linkage);
  REQUIRE(drawing.rows.size() == table.size());
  std::size_t unassembled = 0, compared = 0;
  for (std::size_t r = 0; r < table.size(); ++r) {
    CAPTURE(r);
    if (table.status(r) == kinema::Status::unassembled) {
      CHECK(drawing.rows[r].empty());
      ++unassembled;
      continue;
    }
    REQUIRE(drawing.rows[r].size() == 2 * drawing.joint_names.size());  // no blocks in a four-bar
    for (std::size_t p = 0; p < model.system.points.size(); ++p)
      for (std::size_t j = 0; j < drawing.joint_names.size(); ++j) {
        if (drawing.joint_names[j] != model.system.points[p].name) continue;
        const kinema::PointMotion point = table.point(r, p);
        CHECK(std::fabs(drawing.rows[r][2 * j] - point.position[0]) < 1e-12);
        CHECK(std::fabs(drawing.rows[r][2 * j + 1] - point.position[1]) < 1e-12);
        ++compared;
      }
  }
  CHECK(unassembled > 0);  // the turn leaves the rocker's range
  CHECK(compared > 0);
}

TEST_CASE("engine/printers/web/page: the file's strings stay data inside their script element") {
  const std::string hostile = "</script><script>alert(1)</script><!--";
  const kinema::Mechanism mechanism = kinema::read_mechanism_text(
      kinema_test::replaced("title = \"four-bar\"",
                            "title = " + nlohmann::json(hostile).dump()),
      "four_bar.toml");
  const kinema::Model model = kinema::make_model(mechanism, kinema::DerivationScope::full);
  const kinema::MotionTable table = kinema::solve_motion(model, turn_in_degrees(30));
  std::ostringstream out;
  kinema::print_page(out, model, table, false);
  const std::string page = out.str();
  CHECK(occurrences(page, "<script") == 2);  // the data and the page's own script
  CHECK(occurrences(page, "</script>") == 2);
  const std::string open = "<script type=\"application/json\" id=\"kinema-data\">";
  const std::size_t begin = page.find(open) + open.size(), end = page.find("</script>", begin);
  const std::string data = page.substr(begin, end - begin);
  CHECK(data.find('<') == std::string::npos);
  const nlohmann::json parsed = nlohmann::json::parse(data);
  CHECK(parsed["title"] == hostile);
  CHECK(parsed["rows"].size() == table.size());
  // The policy names the page's script and style only, by the digests of what the page holds
  // (the script's tape runner is generated when the page is written).
  const std::string script_open = "</script>\n<script>", style_open = "<style>";
  const std::size_t script_begin = page.find(script_open) + script_open.size();
  const std::string script = page.substr(script_begin, page.find("</script>", script_begin) - script_begin);
  const std::size_t style_begin = page.find(style_open) + style_open.size();
  const std::string style = page.substr(style_begin, page.find("</style>", style_begin) - style_begin);
  CHECK(script.find("kinemaTapeRunner") != std::string::npos);
  CHECK(page.find("script-src 'sha256-" + kinema::base64_of_hex(kinema::sha256_hex(script)) + "'; style-src 'sha256-" +
                  kinema::base64_of_hex(kinema::sha256_hex(style)) + "';") != std::string::npos);
}

TEST_CASE("engine/base/sha256: the digests of FIPS 180-4's examples") {
  CHECK(kinema::sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(kinema::sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(kinema::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");  // two blocks
  CHECK(kinema::sha256_hex(std::string(1000000, 'a')) == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// The data a sample's page carries (a turn at 30 deg steps).
nlohmann::json page_data(const std::string& name) {
  const kinema::Model model = kinema::load_model(kinema_test::sample(name));
  const kinema::MotionTable table = kinema::solve_motion(model, turn_in_degrees(30));
  std::ostringstream out;
  kinema::print_page(out, model, table, false);
  const std::string page = out.str(), open = "id=\"kinema-data\">";
  const std::size_t begin = page.find(open) + open.size();
  return nlohmann::json::parse(page.substr(begin, page.find("</script>", begin) - begin));
}

TEST_CASE("engine/printers/web/page: vector-loop, joints and chain files' pages carry what solving again needs") {
  const nlohmann::json six_bar = page_data("problem_4_4_six_bar.toml")["resolve"];
  REQUIRE(six_bar.is_object());
  CHECK(six_bar["inputs"].size() == 12);
  // EF = "CE" and Lc = "CD" follow their parameters: no slider, set by the formulas' tape.
  std::vector<std::string> sliders, followers;
  for (const auto& p : six_bar["parameters"]) (p["slider"] ? sliders : followers).push_back(p["name"]);
  CHECK(sliders == std::vector<std::string>{"AB", "BC", "CD", "CE", "La", "Lb"});
  CHECK(followers == std::vector<std::string>{"EF", "Lc"});
  CHECK(six_bar["formula_targets"].size() == 2);
  CHECK(six_bar["tape"]["code"].size() % 6 == 0);
  // Joints and links: each drawn joint found on the drawing stage, and a kind for each
  // extra column (block angle and rates, slider terms, relative turning).
  const nlohmann::json joints = page_data("problem_4_4_joints.toml");
  REQUIRE(joints["resolve"].is_object());
  const nlohmann::json& linkage = joints["resolve"]["linkage"];
  REQUIRE(linkage.is_object());
  CHECK(linkage["joints"].size() == joints["drawing"]["joint_names"].size());
  CHECK(linkage["block_count"] == 1);  // slider 5
  CHECK(linkage["guide_count"] == 1);  // its guide x = -Lc
  CHECK(linkage["column_kinds"].size() == 3 + 6 + 2);  // theta5; F5's vrel, arel, Coriolis; omega54, alpha54
  CHECK(page_data("robot_arm_seed000.toml")["resolve"]["frame_count"] == 3);
  // Each slider's range is the analysis's over the page's rows (engine/analysis/slider_ranges); a follower has none.
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  const kinema::MotionTable table = kinema::solve_motion(model, turn_in_degrees(30));
  const kinema::Resolving analysed = *kinema::resolving(model, &table);
  for (std::size_t k = 0; k < analysed.parameters.size(); ++k) {
    const kinema::Resolving::Parameter& p = analysed.parameters[k];
    const nlohmann::json& written = six_bar["parameters"][k];
    INFO(p.name);
    REQUIRE(written.contains("range") == p.slider);
    if (!p.slider) continue;
    CHECK(written["range"]["min"].get<double>() == p.range.min);
    CHECK(written["range"]["max"].get<double>() == p.range.max);
    CHECK(written["range"]["whole_min"].get<double>() == p.range.whole_min);
    CHECK(written["range"]["whole_max"].get<double>() == p.range.whole_max);
    CHECK((p.range.min < p.value && p.value < p.range.max));
  }
}

// A plot shows one unit: the crank-shaper's ram (mm/s) and its links' rates (rad/s) each get
// their own, and every rate, second rate and speed is on one plot.
TEST_CASE("engine/printers/web/page: each plot's curves share one unit") {
  for (const char* name : {"crank_shaper.toml", "example_4_2_joints.toml", "four_bar.toml"}) {
    const std::string sample = name;
    CAPTURE(sample);
    const nlohmann::json data = page_data(name);
    const nlohmann::json& fields = data["columns"]["fields"];
    std::set<std::size_t> plotted;
    std::set<std::string> titles;
    for (const nlohmann::json& plot : data["columns"]["plots"]) {
      std::set<std::string> units;
      for (const nlohmann::json& f : plot["fields"]) {
        units.insert(fields[f.get<std::size_t>()]["unit"].get<std::string>());
        CHECK(plotted.insert(f.get<std::size_t>()).second);
      }
      CHECK(units.size() == 1);
      CHECK(titles.insert(plot["title"].get<std::string>()).second);
    }
    // Every coordinate's rate and second rate (CSV fields after the input's three and the
    // status) and every point's speed, plotted once.
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const std::size_t n = model.system.unknowns.size();
    CHECK(plotted.size() == 2 * n + model.system.points.size());
    for (std::size_t k = 0; k < n; ++k) CHECK((plotted.count(4 + 3 * k + 1) && plotted.count(4 + 3 * k + 2)));
    if (sample != "four_bar.toml") CHECK(titles.count("rates") == 0);  // mixed units: split
    if (sample == "four_bar.toml") CHECK(titles.count("rates") == 1);
  }
}

TEST_CASE("engine/printers/web/page: base64 of hex digests as RFC 4648 gives them") {
  CHECK(kinema::base64_of_hex("") == "");
  CHECK(kinema::base64_of_hex("66") == "Zg==");
  CHECK(kinema::base64_of_hex("666f") == "Zm8=");
  CHECK(kinema::base64_of_hex("666f6f") == "Zm9v");
  CHECK(kinema::base64_of_hex("666f6f626172") == "Zm9vYmFy");
}

// The page's constructions are the analysis's, written compactly: decoding a row gives back
// every centre found by Kennedy lines (those at joints are named by the joint) and every
// polygon vertex, to the five digits the page draws.
TEST_CASE("engine/printers/web/page_constructions: each row's centres and polygons are the analysis's") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_joints.toml"), kinema::DerivationScope::evaluation);
  const kinema::MotionTable table = kinema::solve_motion(model, turn_in_degrees(45));
  kinema::ViewNeeds needs;
  needs.motion = true;
  const kinema::Analysis analysis = kinema::analyse_for_views(model, &table, needs);
  REQUIRE(analysis.motion);
  const nlohmann::ordered_json data = kinema::constructions_json(analysis.values, *analysis.motion, 1.0, {});
  REQUIRE(data["rows"].size() == table.size());
  const auto close = [](double page, double engine, double size) { return std::fabs(page - engine) <= 1e-4 * size; };
  std::size_t centres = 0, vertices = 0;
  for (std::size_t r = 0; r < table.size(); ++r) {
    const kinema::ValueAnalysis& value = analysis.values[r];
    REQUIRE(value.centres);
    REQUIRE(value.polygons);
    const auto& row = data["rows"][r];
    const auto& structure = data["centre_structures"][row["centres"][0].get<std::size_t>()];
    REQUIRE(structure["centres"].size() == value.centres->centres.size());
    // Each centre's Kennedy lines, from the row's set: one line per two centres it passes through.
    const auto& kennedy = data["kennedy_sets"][row["centres"][1].get<std::size_t>()];
    REQUIRE(kennedy.size() == value.centres->centres.size());
    for (std::size_t c = 0; c < kennedy.size(); ++c) CHECK(2 * kennedy[c].size() == value.centres->centres[c].kennedy.size());
    std::size_t k = 2;
    for (std::size_t c = 0; c < value.centres->centres.size(); ++c) {
      const kinema::InstantCentre& centre = value.centres->centres[c];
      const auto& written = structure["centres"][c];
      if (centre.at_infinity || written["joint"].is_null()) {
        CHECK(close(row["centres"][k].get<double>(), centre.at.real(), 1.0));
        CHECK(close(row["centres"][k + 1].get<double>(), centre.at.imag(), 1.0));
        k += 2;
        ++centres;
      } else {
        const std::size_t j = written["joint"];
        CHECK(std::abs(centre.at - std::complex<double>(analysis.motion->rows[r][2 * j], analysis.motion->rows[r][2 * j + 1])) < 1e-12);
      }
      if (written["seen_from"].get<bool>()) k += 2;
    }
    CHECK(k == row["centres"].size());
    for (int order = 0; order < 2; ++order) {
      const kinema::Polygon& polygon = order == 0 ? value.polygons->first : value.polygons->second;
      const auto& p = row["polygons"][order];
      double size = 0;
      for (const kinema::PolygonVertex& v : polygon.vertices) size = std::max(size, std::abs(v.at));
      const auto& written = data["polygon_structures"][p[0].get<std::size_t>()]["vertices"];
      std::size_t k = 1;
      for (std::size_t v = 0; v < polygon.vertices.size(); ++v, ++vertices) {
        if (written[v].contains("pole")) {  // the pole is at 0, said once
          CHECK(std::abs(polygon.vertices[v].at) <= 1e-12 * size);
          continue;
        }
        CHECK(close(p[k].get<double>(), polygon.vertices[v].at.real(), size));
        CHECK(close(p[k + 1].get<double>(), polygon.vertices[v].at.imag(), size));
        k += 2;
      }
    }
  }
  CHECK(centres >= table.size());  // a Kennedy centre or one at infinity in every row
  CHECK(vertices >= 8 * table.size());
}

// Issue 45: a pin's centre is in the page's data at every row, at the joint the row draws,
// and marked a pin (a page that solves again puts it where it draws that joint): the
// vector-loop four-bar at theta2 = 0, where its coupler and rocker turn alike, and Problem
// 4.4 as joints and links at its slider's limit positions (links 3, 4 and 5 at rest there).
TEST_CASE("engine/printers/web/page_constructions: every pin's centre at its joint in the rows, marked a pin") {
  for (const char* name : {"four_bar.toml", "problem_4_4_joints.toml"}) {
    CAPTURE(std::string(name));
    const kinema::Model model = kinema::load_model(kinema_test::sample(name), kinema::DerivationScope::evaluation);
    std::vector<double> inputs = {0.0, 0.5};
    if (model.system.plan)
      for (const kinema::Strokes& s : kinema::slider_strokes(model))
        for (double limit : s.limit_inputs) inputs.push_back(limit * M_PI / 180);
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    kinema::ViewNeeds needs;
    needs.motion = true;
    const kinema::Analysis analysis = kinema::analyse_for_views(model, &table, needs);
    REQUIRE(analysis.motion);
    const nlohmann::ordered_json data = kinema::constructions_json(analysis.values, *analysis.motion, 1.0, {});
    const std::size_t pins = model.system.plan ? model.system.plan->pins.size() : 4;  // O2, A, B, O4
    for (std::size_t r = 0; r < table.size(); ++r) {
      CAPTURE(r);
      REQUIRE(table.status(r) == kinema::Status::ok);
      const auto& structure = data["centre_structures"][data["rows"][r]["centres"][0].get<std::size_t>()];
      // (At the six-bar's slider limits links 3, 4 and 5 are at rest with ground: I04 and
      // I35 are any point. The four-bar's pairs all have a centre.)
      if (!model.system.plan) CHECK(structure["not_found"].empty());
      std::size_t marked = 0;
      for (std::size_t c = 0; c < structure["centres"].size(); ++c) {
        const auto& written = structure["centres"][c];
        const kinema::InstantCentre& centre = analysis.values[r].centres->centres[c];
        CHECK(written.value("pin", false) == centre.pin);
        if (!centre.pin) continue;
        ++marked;
        REQUIRE(!written["joint"].is_null());
        const std::size_t j = written["joint"];
        CHECK(std::abs(centre.at - std::complex<double>(analysis.motion->rows[r][2 * j], analysis.motion->rows[r][2 * j + 1])) <
              1e-12);
      }
      CHECK(marked == pins);
    }
  }
}

// Issue 35's target: Problem 4.4 at 0.5 deg steps (kinema page --sweep 0:360:0.5, 721 rows)
// in a file of at most 1 MB, in both its forms (the vector loops' page carries the tape too).
TEST_CASE("engine/printers/web/page: Problem 4.4's pages at 0.5 deg steps are at most 1 MB" * doctest::skip(kinema_test::kSanitized)) {
  std::vector<double> inputs;
  for (int k = 0; k <= 720; ++k) inputs.push_back(k * 0.5 * M_PI / 180);
  for (const char* name : {"problem_4_4_six_bar.toml", "problem_4_4_joints.toml"}) {
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    std::ostringstream out;
    kinema::print_page(out, model, table, false);
    MESSAGE(std::string(name) << ": " << out.str().size() << " bytes");
    CHECK(out.str().size() <= 1000000);
  }
}
