// Results for programs (schema in README.md).
#include <iomanip>
#include <nlohmann/json.hpp>

#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/diagnostics.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {
namespace {

class JsonPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::results; }
  const char* name() const override { return "json"; }

  void print(std::ostream& out, const PrintJob& job) const override {
    using json = nlohmann::ordered_json;
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const Driver& input = system.input;
    const Dimension input_kind = input.dimension;
    auto kind_name = [](Dimension d) { return d == Dimension::angle ? "angle" : "length"; };
    // With --precision a number is rounded to that many significant digits (JSON then
    // prints its shortest form); without, every double is written to round-trip.
    const auto num = [&](double value) { return job.precision > 0 ? round_significant(value, job.precision) : value; };
    json doc;
    doc["title"] = system.title;
    doc["units"] = {{"angle", "deg"},
                    {"angular_rate", "rad/s"},
                    {"angular_second_rate", "rad/s^2"},
                    {"length", scale.length_unit},
                    {"velocity", scale.length_unit + "/s"},
                    {"acceleration", scale.length_unit + "/s^2"}};
    doc["input"] = {{"name", input.name},
                    {"kind", kind_name(input_kind)},
                    {"rate_name", input.rate.get_name()},
                    {"second_rate_name", input.second_rate.get_name()}};
    json coordinates = json::array();
    for (const Coordinate& q : system.unknowns) {
      coordinates.push_back({{"name", q.name},
                             {"kind", kind_name(q.dimension)},
                             {"rate_name", q.rate.get_name()},
                             {"second_rate_name", q.second_rate.get_name()}});
    }
    doc["coordinates"] = coordinates;
    json points = json::array();
    for (const PointObservable& p : system.points) points.push_back(p.name);
    doc["points"] = points;
    json results = json::array();
    for (const MotionState& s : *job.values) {
      json row;
      row["input"] = num(scale.input(s.input));
      row["input_rate"] = num(scale.rate(input_kind, s.input_rate));
      row["input_second_rate"] = num(scale.rate(input_kind, s.input_second_rate));
      row["status"] = status_name(s.status);
      const std::string message = describe_failure(system, s);
      if (!message.empty()) row["message"] = message;
      json values = json::object();
      if (s.status != Status::unassembled) {
        for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
          const Dimension kind = system.unknowns[i].dimension;
          json c = {{"value", num(scale.coordinate(kind, s.q[i]))}, {"rate", nullptr}, {"second_rate", nullptr}};
          if (s.status == Status::ok) {
            c["rate"] = num(scale.rate(kind, s.qd[i]));
            c["second_rate"] = num(scale.rate(kind, s.qdd[i]));
          }
          values[system.unknowns[i].name] = c;
        }
        row["loop_residual"] = num(s.loop_residual / scale.length);
      }
      row["coordinates"] = values;
      json motion = json::object();
      if (s.status == Status::ok) {
        const double f = scale.length;
        for (std::size_t p = 0; p < system.points.size(); ++p) {
          const PointMotion& m = s.points[p];
          json position = json::array(), velocity = json::array(), acceleration = json::array();
          for (std::size_t c = 0; c < m.dimension; ++c) {
            position.push_back(num(m.position[c] / f));
            velocity.push_back(num(m.velocity[c] / f));
            acceleration.push_back(num(m.acceleration[c] / f));
          }
          motion[system.points[p].name] = {{"position", position},
                                           {"velocity", velocity},
                                           {"speed", num(m.speed() / f)},
                                           {"acceleration", acceleration},
                                           {"acceleration_magnitude", num(m.acceleration_magnitude() / f)}};
        }
      }
      row["points"] = motion;
      results.push_back(row);
    }
    doc["results"] = results;
    out << std::setw(2) << doc << "\n";
  }
};

}  // namespace

const Printer& json_printer() {
  static const JsonPrinter printer;
  return printer;
}

}  // namespace kinema
