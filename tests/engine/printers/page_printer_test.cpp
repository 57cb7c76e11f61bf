// kinema page's C++ half: the drawing's geometry at every row (engine/analysis/motion_drawing)
// and the page printer's escaping and policy (engine/printers/web/page). What the page does
// with them in a browser is tests/browser/page_test.js.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "engine/model.hpp"
#include "engine/printers/web/page.hpp"
#include "engine/analysis/motion_drawing.hpp"
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
  const kinema::MotionTable table = kinema::analyse(model, turn_in_degrees(10));
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
  const kinema::Model model = kinema::make_model(mechanism, kinema::DerivationScope::evaluation);
  const kinema::MotionTable table = kinema::analyse(model, turn_in_degrees(30));
  kinema::PrintJob job{model, &table};
  std::ostringstream out;
  kinema::write_page(out, job, kinema::motion_drawing(model, table));
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
  // The policy names the page's script and style only.
  CHECK(page.find("default-src 'none'; script-src 'sha256-") != std::string::npos);
}

TEST_CASE("engine/printers/web/page: base64 of hex digests as RFC 4648 gives them") {
  CHECK(kinema::base64_of_hex("") == "");
  CHECK(kinema::base64_of_hex("66") == "Zg==");
  CHECK(kinema::base64_of_hex("666f") == "Zm8=");
  CHECK(kinema::base64_of_hex("666f6f") == "Zm9v");
  CHECK(kinema::base64_of_hex("666f6f626172") == "Zm9vYmFy");
}
