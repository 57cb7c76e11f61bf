// kinema against what a user would pick instead, per input value, in one run:
// kinema's compiled evaluator (Newton warm-started + velocity + acceleration +
// points), a hand-written closed form (the practical floor), GiNaC subs+evalf
// and GiNaC compile_ex of the same derived expressions, the SymPy route
// (bench/sympy_route.py) and the derivation itself (file -> ready evaluator).
// Run: ./build/kinema_bench   (prints Google Benchmark's table, then the ratios)
// "kinema" is one value per call (Workspace::advance from the previous value);
// "kinema sweep" is solve_motion() over a revolution (SIMD blocks of 32 values).
#include <benchmark/benchmark.h>
#include <ginac/ginac.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include <kinema/kinema.hpp>

#include "engine/analysis/design_study.hpp"
#include "engine/model.hpp"

namespace {

constexpr int kAngles = 3600;  // one revolution in 0.1 deg steps

std::string sample_path(const std::string& name) { return std::string(KINEMA_SAMPLES_DIR) + "/" + name; }

struct Case {
  std::unique_ptr<kinema::Model> model;
  std::vector<double> angles;            // SI, one revolution from the file's value
  std::vector<Eigen::VectorXd> solutions;  // kinema's positions, for the symbolic routes
};

Case& case_for(const std::string& name) {
  static std::map<std::string, Case> cases;
  auto found = cases.find(name);
  if (found != cases.end()) return found->second;
  Case c;
  c.model = std::make_unique<kinema::Model>(kinema::load_model(sample_path(name)));
  const double start = c.model->system.input.values.at(0);
  for (int i = 0; i < kAngles; ++i) c.angles.push_back(start + 2 * M_PI * i / kAngles);
  const auto states = kinema::solve_motion(*c.model, c.angles);
  for (const auto& s : states) c.solutions.push_back(s.q);
  return cases.emplace(name, std::move(c)).first->second;
}

// --- kinema ---------------------------------------------------------------
void kinema_scalar(benchmark::State& state, const std::string& name) {
  Case& c = case_for(name);
  const auto& input = c.model->system.input;
  kinema::Workspace workspace(*c.model);
  kinema::MotionState s = workspace.motion(c.angles[0], input.rate_value, input.second_rate_value, c.solutions[0]);
  std::size_t i = 1;
  for (auto _ : state) {
    // One call per value, each from the last one, as a controller or a simulation steps
    // (revolution after revolution).
    const double theta = c.angles[i % c.angles.size()] + 2 * M_PI * static_cast<double>(i / c.angles.size());
    if (!workspace.advance(theta, input.rate_value, input.second_rate_value, s)) state.SkipWithError("lost the branch");
    benchmark::DoNotOptimize(s.qdd.data());
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

// What `kinema eval --sweep` does: solve_motion() over the revolution (continuation with a
// predictor from the previous rates, results stored per angle).
void kinema_sweep(benchmark::State& state, const std::string& name) {
  Case& c = case_for(name);
  for (auto _ : state) {
    const auto states = kinema::solve_motion(*c.model, c.angles);
    benchmark::DoNotOptimize(states.q(states.size() - 1).data());
  }
  state.SetItemsProcessed(state.iterations() * c.angles.size());
}

// The large job: Problem 4.4 over 10^6 values of one revolution, results kept.
void kinema_sweep_million(benchmark::State& state, unsigned threads) {
  Case& c = case_for("problem_4_4_six_bar.toml");
  kinema::MotionOptions options;
  options.threads = threads;
  constexpr std::size_t kValues = 1000000;
  std::vector<double> angles(kValues);
  for (std::size_t i = 0; i < kValues; ++i) angles[i] = c.angles[0] + 2 * M_PI * static_cast<double>(i) / kValues;
  std::size_t bytes = 0, batch_rows = 0;
  for (auto _ : state) {
    const auto table = kinema::solve_motion(*c.model, angles, options);
    benchmark::DoNotOptimize(table.q(kValues - 1).data());
    bytes = table.bytes();
    batch_rows = table.batch_rows();
  }
  state.counters["table_MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["batch_share"] = static_cast<double>(batch_rows) / kValues;
}

void derivation(benchmark::State& state, const std::string& name) {
  for (auto _ : state) {
    kinema::Model model = kinema::load_model(sample_path(name));
    benchmark::DoNotOptimize(&model.kinematics);
  }
  state.SetItemsProcessed(state.iterations());
}

// A design study's step: the model with its first parameter 1 % longer, nothing derived
// or compiled (issue 36's target: <= 50 us).
void with_parameters(benchmark::State& state, const std::string& name) {
  Case& c = case_for(name);
  const kinema::SystemParameter& first = c.model->system.parameters.at(0);
  const std::vector<std::pair<std::string, double>> values{{first.symbol.get_name(), 1.01 * first.value}};
  for (auto _ : state) {
    kinema::Model copy = kinema::with_parameters(*c.model, values);
    benchmark::DoNotOptimize(&copy.kinematics);
  }
}

// One value through the library's facade (MechanismModel::solve, results read by name
// later): the C++ call the Python module's Model.at is measured against (issue 36: the
// module adds at most 2 us).
void facade_solve(benchmark::State& state, const std::string& name) {
  const kinema::MechanismModel model(sample_path(name));
  double value = 0.5;
  for (auto _ : state) {
    const kinema::Solution solution = model.solve(value);
    benchmark::DoNotOptimize(solution.rates().data());
    value = value < 6.0 ? value + 1e-3 : 0.5;  // a new value each time, near the last (as a sweep in Python asks)
  }
}

// A design study (issue 36): 100,000 four-bar designs (coupler and rocker lengths on a
// 400 x 250 grid) x 361 crank angles, every figure (Grashof class, least transmission
// angle, time ratio, assembly, largest rates, second rates, speeds and accelerations), on
// `threads` threads. Target: <= 1 s on two cores.
void design_study(benchmark::State& state, unsigned threads) {
  Case& c = case_for("four_bar.toml");
  std::vector<double> b, cc, inputs;
  for (int i = 0; i < 400; ++i) b.push_back(0.100 + 0.040 * i / 400);
  for (int i = 0; i < 250; ++i) cc.push_back(0.060 + 0.040 * i / 250);
  for (int k = 0; k <= 360; ++k) inputs.push_back(k * kinema::kPi / 180);
  const kinema::Designs designs = kinema::design_grid({"b", "c"}, {b, cc});
  kinema::StudyOptions options;
  options.threads = threads;
  for (auto _ : state) {
    const kinema::StudyResults results = kinema::run_design_study(*c.model, designs, inputs, options);
    benchmark::DoNotOptimize(results.max_rate.data());
  }
  state.counters["values/s"] = benchmark::Counter(double(designs.size() * inputs.size()), benchmark::Counter::kIsIterationInvariantRate);
}

// --- hand-written closed forms (the floor) --------------------------------
struct FourBarResult {
  double t3, t4, w3, w4, a3, a4;
};
FourBarResult four_bar_closed_form(double t2, double w2, double a2) {
  const double a = 0.04, b = 0.12, c = 0.08, d = 0.1;  // samples/four_bar.toml
  const double ax = a * std::cos(t2), ay = a * std::sin(t2);
  const double diagonal = std::hypot(d - ax, ay);
  const double t3 = std::atan2(-ay, d - ax) + std::acos((b * b + diagonal * diagonal - c * c) / (2 * b * diagonal));
  const double t4 = std::atan2(ay + b * std::sin(t3), ax + b * std::cos(t3) - d);
  const double w3 = a * w2 * std::sin(t4 - t2) / (b * std::sin(t3 - t4));
  const double w4 = a * w2 * std::sin(t2 - t3) / (c * std::sin(t4 - t3));
  const double a3 = (-a * a2 * std::sin(t2 - t4) - a * w2 * w2 * std::cos(t2 - t4) - b * w3 * w3 * std::cos(t3 - t4) +
                     c * w4 * w4) / (b * std::sin(t3 - t4));
  const double a4 = (a * a2 * std::sin(t2 - t3) + a * w2 * w2 * std::cos(t2 - t3) + b * w3 * w3 -
                     c * w4 * w4 * std::cos(t4 - t3)) / (c * std::sin(t4 - t3));
  return {t3, t4, w3, w4, a3, a4};
}

struct SliderCrankResult {
  double t3, x, w3, v, a3, acc;
};
SliderCrankResult slider_crank_closed_form(double t2, double w2, double a2) {
  const double a = 0.05, b = 0.15, e = 0.01;  // samples/slider_crank.toml
  const double t3 = std::asin((e - a * std::sin(t2)) / b);
  const double x = a * std::cos(t2) + b * std::cos(t3);
  const double w3 = -a * w2 * std::cos(t2) / (b * std::cos(t3));
  const double v = -a * w2 * std::sin(t2) - b * w3 * std::sin(t3);
  const double a3 = (a * w2 * w2 * std::sin(t2) - a * a2 * std::cos(t2) + b * w3 * w3 * std::sin(t3)) / (b * std::cos(t3));
  const double acc = -a * a2 * std::sin(t2) - a * w2 * w2 * std::cos(t2) - b * a3 * std::sin(t3) - b * w3 * w3 * std::cos(t3);
  return {t3, x, w3, v, a3, acc};
}

void closed_form_four_bar(benchmark::State& state) {
  Case& c = case_for("four_bar.toml");
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(four_bar_closed_form(c.angles[i], 10.0, 0.0));
    i = (i + 1) % c.angles.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void closed_form_slider_crank(benchmark::State& state) {
  Case& c = case_for("slider_crank.toml");
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(slider_crank_closed_form(c.angles[i], 100 * M_PI, 0.0));
    i = (i + 1) % c.angles.size();
  }
  state.SetItemsProcessed(state.iterations());
}

// --- GiNaC routes on the same derived expressions -------------------------
// The rates and second rates as solved by the derivation, evaluated at kinema's
// positions: the symbolic routes get the position solve for free.
std::vector<GiNaC::ex> rate_expressions(const kinema::Derivation& d) {
  std::vector<GiNaC::ex> all(d.solved_rates.begin(), d.solved_rates.end());
  all.insert(all.end(), d.solved_second_rates.begin(), d.solved_second_rates.end());
  return all;
}

void ginac_subs_evalf(benchmark::State& state, const std::string& name) {
  Case& c = case_for(name);
  const kinema::Derivation& d = c.model->derivation;
  const kinema::ConstraintSystem& system = c.model->system;
  const auto& input = system.input;
  std::size_t i = 0;
  for (auto _ : state) {
    GiNaC::exmap values;
    for (const auto& parameter : system.parameters) values[parameter.symbol] = parameter.value;
    values[input.symbol] = c.angles[i];
    values[input.rate] = input.rate_value;
    values[input.second_rate] = input.second_rate_value;
    for (std::size_t j = 0; j < system.unknowns.size(); ++j) values[system.unknowns[j].symbol] = c.solutions[i][j];
    // Blocks in order: later rates use earlier ones' values.
    for (const auto& block : d.blocks)
      for (std::size_t j : block.unknowns)
        values[system.unknowns[j].rate] = GiNaC::evalf(d.solved_rates[j].subs(values));
    for (const auto& block : d.blocks)
      for (std::size_t j : block.unknowns)
        values[system.unknowns[j].second_rate] = GiNaC::evalf(d.solved_second_rates[j].subs(values));
    benchmark::DoNotOptimize(values.size());
    i = (i + 1) % c.angles.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void ginac_compile_ex(benchmark::State& state, const std::string& name) {
  Case& c = case_for(name);
  const kinema::Derivation& d = c.model->derivation;
  const kinema::ConstraintSystem& system = c.model->system;
  const auto& input = system.input;
  // compile_ex takes a flat list of expressions in a flat list of symbols; the
  // block structure is unrolled by substitution so each output stands alone.
  GiNaC::exmap rates, second_rates;
  for (const auto& block : d.blocks)
    for (std::size_t j : block.unknowns) rates[system.unknowns[j].rate] = d.solved_rates[j].subs(rates);
  for (const auto& block : d.blocks)
    for (std::size_t j : block.unknowns)
      second_rates[system.unknowns[j].second_rate] = d.solved_second_rates[j].subs(second_rates).subs(rates);
  GiNaC::lst outputs, symbols;
  for (const auto& [symbol, e] : rates) outputs.append(e);
  for (const auto& [symbol, e] : second_rates) outputs.append(e);
  for (const auto& parameter : system.parameters) symbols.append(parameter.symbol);
  symbols.append(input.symbol);
  symbols.append(input.rate);
  symbols.append(input.second_rate);
  for (const auto& q : system.unknowns) symbols.append(q.symbol);
  GiNaC::FUNCP_CUBA function = nullptr;
  try {
    GiNaC::compile_ex(outputs, symbols, function);
  } catch (const std::exception& error) {
    state.SkipWithError(error.what());
    return;
  }
  std::vector<double> in(symbols.nops()), out(outputs.nops());
  for (std::size_t p = 0; p < system.parameters.size(); ++p) in[p] = system.parameters[p].value;
  const std::size_t base = system.parameters.size();
  const int in_count = static_cast<int>(in.size()), out_count = static_cast<int>(out.size());
  std::size_t i = 0;
  for (auto _ : state) {
    in[base] = c.angles[i];
    in[base + 1] = input.rate_value;
    in[base + 2] = input.second_rate_value;
    for (std::size_t j = 0; j < system.unknowns.size(); ++j) in[base + 3 + j] = c.solutions[i][j];
    function(&in_count, in.data(), &out_count, out.data());
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) % c.angles.size();
  }
  state.SetItemsProcessed(state.iterations());
}

// Keeps each benchmark's time per item for the ratio table.
class Collector : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> ns_per_item;
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      ns_per_item[run.benchmark_name()] = run.GetAdjustedRealTime() *
                                          (run.time_unit == benchmark::kMillisecond ? 1e6 : 1.0);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> samples = {"four_bar.toml", "slider_crank.toml", "problem_4_4_six_bar.toml"};
  for (const auto& s : samples) {
    benchmark::RegisterBenchmark(("kinema/" + s).c_str(), kinema_scalar, s);
    benchmark::RegisterBenchmark(("kinema_sweep/" + s).c_str(), kinema_sweep, s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ginac_subs_evalf/" + s).c_str(), ginac_subs_evalf, s);
    benchmark::RegisterBenchmark(("ginac_compile_ex/" + s).c_str(), ginac_compile_ex, s);
    benchmark::RegisterBenchmark(("derivation/" + s).c_str(), derivation, s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("with_parameters/" + s).c_str(), with_parameters, s)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("facade_solve/" + s).c_str(), facade_solve, s)->Unit(benchmark::kMicrosecond);
  }
  for (unsigned threads : {1u, 2u}) {
    benchmark::RegisterBenchmark(("kinema_sweep_1e6/problem_4_4_six_bar.toml/threads:" + std::to_string(threads)).c_str(),
                                 kinema_sweep_million, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  for (unsigned threads : {1u, 2u}) {
    benchmark::RegisterBenchmark(("design_study_1e5x361/four_bar.toml/threads:" + std::to_string(threads)).c_str(),
                                 design_study, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  }
  benchmark::RegisterBenchmark("closed_form/four_bar.toml", closed_form_four_bar);
  benchmark::RegisterBenchmark("closed_form/slider_crank.toml", closed_form_slider_crank);
  benchmark::Initialize(&argc, argv);
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);

  // Sanity: the closed forms agree with kinema (they are the floor, not a different job).
  {
    Case& c = case_for("four_bar.toml");
    kinema::Workspace w(*c.model);
    const auto s = w.motion(c.angles[100], 10.0, 0.0, c.solutions[100]);
    const auto f = four_bar_closed_form(c.angles[100], 10.0, 0.0);
    std::printf("\nclosed-form check (four-bar at %.1f deg): omega3 %.12g vs %.12g, alpha4 %.12g vs %.12g\n",
                c.angles[100] * 180 / M_PI, s.qd[0], f.w3, s.qdd[1], f.a4);
  }

  // The SymPy route, measured by its own script in the same run.
  nlohmann::json sympy;
  const std::string command = "/usr/bin/python3 " + std::string(KINEMA_SOURCE_DIR) + "/bench/sympy_route.py --json 2>/dev/null";
  if (FILE* pipe = popen(command.c_str(), "r")) {
    std::string text;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
    if (pclose(pipe) == 0) sympy = nlohmann::json::parse(text, nullptr, false);
  }
  const std::map<std::string, std::string> sympy_key = {
      {"four_bar.toml", "four_bar"}, {"slider_crank.toml", "slider_crank"}, {"problem_4_4_six_bar.toml", "problem_4_4"}};

  auto get = [&](const std::string& key) {
    auto found = collector.ns_per_item.find(key);
    return found == collector.ns_per_item.end() ? NAN : found->second;
  };
  std::printf("\nPer input value (position + velocity + acceleration), ns; ratio = other / kinema one at a time"
              " | other / kinema sweep\n");
  std::printf("%-26s %8s %8s %22s %24s %22s %22s\n", "mechanism", "kinema", "sweep", "closed form",
              "GiNaC subs+evalf", "GiNaC compile_ex", "SymPy route");
  for (const auto& s : samples) {
    const double k = get("kinema/" + s);
    const double sweep = get("kinema_sweep/" + s) / kAngles;  // ns per sweep / angles
    const double closed = get("closed_form/" + s), subs = get("ginac_subs_evalf/" + s),
                 compiled = get("ginac_compile_ex/" + s);
    double sympy_ns = NAN;
    if (sympy.is_object() && sympy.contains(sympy_key.at(s))) sympy_ns = sympy[sympy_key.at(s)]["per_angle_ns"].get<double>();
    auto ratio = [](double r) {
      char text[32];
      std::snprintf(text, sizeof text, r >= 100 ? "%.0fx" : "%.2fx", r);
      return std::string(text);
    };
    auto cell = [&](double other) {
      if (std::isnan(other)) return std::string("-");
      char text[32];
      std::snprintf(text, sizeof text, "%.0f", other);
      return std::string(text) + " (" + ratio(other / k) + "|" + ratio(other / sweep) + ")";
    };
    std::printf("%-26s %8.0f %8.1f %22s %24s %22s %22s\n", s.c_str(), k, sweep, cell(closed).c_str(),
                cell(subs).c_str(), cell(compiled).c_str(), cell(sympy_ns).c_str());
  }
  const double million = get("kinema_sweep_1e6/problem_4_4_six_bar.toml/threads:1/real_time") / 1e6;
  const double million2 = get("kinema_sweep_1e6/problem_4_4_six_bar.toml/threads:2/real_time") / 1e6;
  std::printf("\nProblem 4.4, 10^6 values of one revolution, results kept: %.0f ms on one thread, %.0f ms on two\n",
              million, million2);
  std::printf("\nDerivation, file to ready evaluator, ms; ratio = SymPy / kinema\n");
  for (const auto& s : samples) {
    const double k = get("derivation/" + s) / 1e6;
    double sympy_ms = NAN;
    if (sympy.is_object() && sympy.contains(sympy_key.at(s))) sympy_ms = sympy[sympy_key.at(s)]["derivation_ms"].get<double>();
    std::printf("%-26s kinema %8.2f   SymPy %8.2f   (%.3gx)\n", s.c_str(), k, sympy_ms, sympy_ms / k);
  }
  std::printf("\nGiNaC subs+evalf and compile_ex evaluate the solved rates at kinema's positions (no position\n"
              "solve); kinema and SymPy include the Newton position solve and the points.\n");
  return 0;
}
