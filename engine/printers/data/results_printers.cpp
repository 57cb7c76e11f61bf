// Table, CSV and JSON printers of motion states.
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include <kinema/engine/printers/printers.hpp>

namespace kinema {
namespace {

std::string number(double value, int significant = 6) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant, value == 0 ? 0.0 : value);  // no "-0"
  return buffer;
}

double input_value(const OutputScale& scale, double si) {
  return scale.input_is_angle ? si * 180.0 / M_PI : si / scale.length;
}

struct Names {
  std::string input_rate, input_second_rate;
  std::vector<std::string> rates, second_rates;
};

Names names_of(const Derivation& d) {
  Names names;
  names.input_rate = d.input_rate.get_name();
  names.input_second_rate = d.input_second_rate.get_name();
  for (const auto& s : d.rates) names.rates.push_back(s.get_name());
  for (const auto& s : d.second_rates) names.second_rates.push_back(s.get_name());
  return names;
}

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

}  // namespace

void print_results_table(std::ostream& out, const Mechanism& m, const Derivation& d,
                         const MotionTable& states) {
  const OutputScale scale(m);
  const Names names = names_of(d);
  const Dimension input_kind = m.input.dimension;
  out << m.title << "\n";
  out << "units: angles deg, angular rates rad/s and rad/s^2, lengths " << scale.length_unit
      << ", velocities " << scale.length_unit << "/s, accelerations " << scale.length_unit << "/s^2\n";
  for (const MotionState& s : states) {
    out << "\n" << m.input.name << " = " << number(input_value(scale, s.input)) << " "
        << scale.coordinate_unit(input_kind) << "   " << names.input_rate << " = "
        << number(scale.rate(input_kind, s.input_rate)) << " " << scale.rate_unit(input_kind) << "   "
        << names.input_second_rate << " = " << number(scale.rate(input_kind, s.input_second_rate)) << " "
        << scale.second_rate_unit(input_kind) << "\n";
    if (s.status == Status::unassembled) {
      out << "  not assembled: " << s.message << "\n";
      continue;
    }
    if (s.status == Status::singular) out << "  SINGULAR: " << s.message << "\n";
    else if (!s.message.empty()) out << "  note: " << s.message << "\n";
    out << "  " << pad("coordinate", 12) << pad("value", 16) << pad("rate", 26) << "second rate\n";
    for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
      const Dimension kind = m.unknowns[i].dimension;
      out << "  " << pad(m.unknowns[i].name, 12)
          << pad(number(scale.coordinate(kind, s.q[i])) + " " + scale.coordinate_unit(kind), 16);
      if (s.status == Status::ok) {
        out << pad(names.rates[i] + " = " + number(scale.rate(kind, s.qd[i])) + " " + scale.rate_unit(kind), 26)
            << names.second_rates[i] << " = " << number(scale.rate(kind, s.qdd[i])) << " "
            << scale.second_rate_unit(kind);
      } else {
        out << "undefined (singular)";
      }
      out << "\n";
    }
    if (s.status != Status::ok || m.points.empty()) continue;
    out << "  " << pad("point", 8) << pad("x", 12) << pad("y", 12) << pad("vx", 12) << pad("vy", 12)
        << pad("|v|", 12) << pad("ax", 12) << pad("ay", 12) << "|a|\n";
    for (std::size_t p = 0; p < m.points.size(); ++p) {
      const PointMotion& pm = s.points[p];
      const double l = scale.length;
      out << "  " << pad(m.points[p].name, 8) << pad(number(pm.x / l), 12) << pad(number(pm.y / l), 12)
          << pad(number(pm.vx / l), 12) << pad(number(pm.vy / l), 12)
          << pad(number(std::hypot(pm.vx, pm.vy) / l), 12) << pad(number(pm.ax / l), 12)
          << pad(number(pm.ay / l), 12) << number(std::hypot(pm.ax, pm.ay) / l) << "\n";
    }
  }
}

void print_results_csv(std::ostream& out, const Mechanism& m, const Derivation& d,
                       const MotionTable& states) {
  const OutputScale scale(m);
  const Names names = names_of(d);
  const Dimension input_kind = m.input.dimension;
  auto column = [](const std::string& name, const std::string& unit) { return name + " [" + unit + "]"; };
  out << column(m.input.name, scale.coordinate_unit(input_kind)) << ","
      << column(names.input_rate, scale.rate_unit(input_kind)) << ","
      << column(names.input_second_rate, scale.second_rate_unit(input_kind)) << ",status";
  for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
    const Dimension kind = m.unknowns[i].dimension;
    out << "," << column(m.unknowns[i].name, scale.coordinate_unit(kind)) << ","
        << column(names.rates[i], scale.rate_unit(kind)) << ","
        << column(names.second_rates[i], scale.second_rate_unit(kind));
  }
  const std::string l = scale.length_unit;
  for (const Point& p : m.points) {
    for (const char* c : {"x", "y"}) out << "," << column(p.name + "_" + c, l);
    for (const char* c : {"vx", "vy", "speed"}) out << "," << column(p.name + "_" + c, l + "/s");
    for (const char* c : {"ax", "ay", "acceleration"}) out << "," << column(p.name + "_" + c, l + "/s^2");
  }
  out << "\n";
  for (const MotionState& s : states) {
    out << number(input_value(scale, s.input), 12) << "," << number(scale.rate(input_kind, s.input_rate), 12)
        << "," << number(scale.rate(input_kind, s.input_second_rate), 12) << "," << status_name(s.status);
    for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
      const Dimension kind = m.unknowns[i].dimension;
      out << ",";
      if (s.status != Status::unassembled) out << number(scale.coordinate(kind, s.q[i]), 12);
      out << ",";
      if (s.status == Status::ok) out << number(scale.rate(kind, s.qd[i]), 12);
      out << ",";
      if (s.status == Status::ok) out << number(scale.rate(kind, s.qdd[i]), 12);
    }
    for (std::size_t p = 0; p < m.points.size(); ++p) {
      if (s.status != Status::ok) {
        out << ",,,,,,,,";
        continue;
      }
      const PointMotion& pm = s.points[p];
      const double f = scale.length;
      for (double v : {pm.x, pm.y, pm.vx, pm.vy, std::hypot(pm.vx, pm.vy), pm.ax, pm.ay,
                       std::hypot(pm.ax, pm.ay)})
        out << "," << number(v / f, 12);
    }
    out << "\n";
  }
}

void print_results_json(std::ostream& out, const Mechanism& m, const Derivation& d,
                        const MotionTable& states) {
  using json = nlohmann::ordered_json;
  const OutputScale scale(m);
  const Names names = names_of(d);
  const Dimension input_kind = m.input.dimension;
  json doc;
  doc["title"] = m.title;
  doc["units"] = {{"angle", "deg"},
                  {"angular_rate", "rad/s"},
                  {"angular_second_rate", "rad/s^2"},
                  {"length", scale.length_unit},
                  {"velocity", scale.length_unit + "/s"},
                  {"acceleration", scale.length_unit + "/s^2"}};
  doc["input"] = {{"name", m.input.name},
                  {"kind", input_kind == Dimension::angle ? "angle" : "length"},
                  {"rate_name", names.input_rate},
                  {"second_rate_name", names.input_second_rate}};
  json coordinates = json::array();
  for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
    coordinates.push_back({{"name", m.unknowns[i].name},
                           {"kind", m.unknowns[i].dimension == Dimension::angle ? "angle" : "length"},
                           {"rate_name", names.rates[i]},
                           {"second_rate_name", names.second_rates[i]}});
  }
  doc["coordinates"] = coordinates;
  json points = json::array();
  for (const Point& p : m.points) points.push_back(p.name);
  doc["points"] = points;
  json results = json::array();
  for (const MotionState& s : states) {
    json row;
    row["input"] = input_value(scale, s.input);
    row["input_rate"] = scale.rate(input_kind, s.input_rate);
    row["input_second_rate"] = scale.rate(input_kind, s.input_second_rate);
    row["status"] = status_name(s.status);
    if (!s.message.empty()) row["message"] = s.message;
    json values = json::object();
    if (s.status != Status::unassembled) {
      for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
        const Dimension kind = m.unknowns[i].dimension;
        json c = {{"value", scale.coordinate(kind, s.q[i])}, {"rate", nullptr}, {"second_rate", nullptr}};
        if (s.status == Status::ok) {
          c["rate"] = scale.rate(kind, s.qd[i]);
          c["second_rate"] = scale.rate(kind, s.qdd[i]);
        }
        values[m.unknowns[i].name] = c;
      }
      row["loop_residual"] = s.loop_residual / scale.length;
    }
    row["coordinates"] = values;
    json motion = json::object();
    if (s.status == Status::ok) {
      const double f = scale.length;
      for (std::size_t p = 0; p < m.points.size(); ++p) {
        const PointMotion& pm = s.points[p];
        motion[m.points[p].name] = {{"position", {pm.x / f, pm.y / f}},
                                    {"velocity", {pm.vx / f, pm.vy / f}},
                                    {"speed", std::hypot(pm.vx, pm.vy) / f},
                                    {"acceleration", {pm.ax / f, pm.ay / f}},
                                    {"acceleration_magnitude", std::hypot(pm.ax, pm.ay) / f}};
      }
    }
    row["points"] = motion;
    results.push_back(row);
  }
  doc["results"] = results;
  out << std::setw(2) << doc << "\n";
}

}  // namespace kinema
