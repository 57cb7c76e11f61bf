// kinema as a Python module: one more view over the library. It reads names and solves
// single values through the facade (<kinema/kinema.hpp>) and prints derivations and
// sweeps with the engine's own printers (the sweep is the npy printer's bytes, read by
// NumPy), so that every number and formula is the one the program prints.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/numpy.h>

#include <kinema/kinema.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <thread>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <variant>

#include "api/engine_access.hpp"
#include "engine/base/errors.hpp"
#include "engine/input_value.hpp"
#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "engine/run/results_stream.hpp"
#include "engine/run/circuit_run.hpp"
#include "engine/run/view.hpp"
#include "engine/analysis/design_study.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/numeric/sweep.hpp"
#include "engine/symbolic/dyad_method.hpp"
#include "readers/mechanism_file.hpp"

namespace py = pybind11;

namespace {

using Value = std::variant<double, std::string>;

/// GiNaC, under the derivations, is not thread-safe (expressions share reference-counted
/// nodes and constants): Python threads take turns in kinema, every call and every
/// model's end holding this. Waited for without the GIL, which the thread in kinema may be
/// waiting for; recursive, as a model's last reference may go within a call. Never
/// destroyed: a model may end after static destructors have run, at the interpreter's exit.
std::recursive_mutex& engine_mutex() {
  static auto* mutex = new std::recursive_mutex;
  return *mutex;
}

class EngineTurn {
 public:
  EngineTurn() {
    if (engine_mutex().try_lock()) return;
    py::gil_scoped_release unlocked;
    engine_mutex().lock();
  }
  ~EngineTurn() { engine_mutex().unlock(); }
  EngineTurn(const EngineTurn&) = delete;
  EngineTurn& operator=(const EngineTurn&) = delete;
};

/// A value of a kind no entry point takes (None, a list where a number goes, text where
/// numbers go): kinema.InputTypeError, both a kinema.InputError (issue 49: every bad input
/// is one) and a TypeError (what issue 45 made with_parameters raise).
class InputTypeError : public kinema::InputError {
 public:
  using kinema::InputError::InputError;
};

/// repr(value) as a message shows it: a long list cut short.
std::string shown(const py::handle& value) {
  std::string text = py::repr(value).cast<std::string>();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

/// Ctrl-C in a long call. Python's SIGINT handler only sets a flag; KeyboardInterrupt is
/// raised when the main thread, holding the GIL, asks for it. run(work) solves on a thread
/// of its own while the caller's thread (the one Python signals) waits: every 50 ms it
/// takes the GIL and asks. An exception a handler raised stops the work (its threads poll
/// check() between blocks, which then throws) and is raised once the work has ended. The
/// caller's thread is not one of the work's threads: those take turns at a mutex, and the
/// caller's thread waiting for its turn there heard nothing for seconds.
class Interruptible {
 public:
  /// From the work's threads, between blocks: stops the work once Python has an exception.
  void check() const {
    if (stop_.load(std::memory_order_relaxed)) throw Stopped{};
  }
  bool stopped() const { return stop_.load(std::memory_order_relaxed); }

  /// Runs `work` (called with the GIL, which it runs without); rethrows its exception, or
  /// the signal handler's. Work of at most kShortRun values runs on the caller's thread,
  /// not heard (under half a second even where no value assembles): a thread to solve on
  /// and the wait for it cost some 0.1 ms, more than a short sweep.
  template <class Work>
  void run(std::size_t values, const Work& work) {
    if (values <= kShortRun) {
      const py::gil_scoped_release unlocked;
      work();
      return;
    }
    std::exception_ptr failure;
    std::optional<py::error_already_set> raised;
    {
      const py::gil_scoped_release unlocked;
      std::mutex mutex;
      std::condition_variable ended;
      bool done = false;
      std::thread worker([&] {
        try {
          work();
        } catch (...) {
          failure = std::current_exception();
        }
        const std::lock_guard<std::mutex> lock(mutex);
        done = true;
        ended.notify_all();
      });
      std::unique_lock<std::mutex> lock(mutex);
      while (!ended.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
        if (raised) continue;
        lock.unlock();
        {
          const py::gil_scoped_acquire held;
          if (PyErr_CheckSignals() != 0) {
            raised.emplace();  // takes the error from Python until it is raised again below
            stop_ = true;
          }
        }
        lock.lock();
      }
      lock.unlock();
      worker.join();
    }
    if (raised) throw *raised;
    if (failure) std::rethrow_exception(failure);
  }

 private:
  static constexpr std::size_t kShortRun = 1000;
  struct Stopped {};  // not a kinema::Error: nothing in the engine takes it for one
  std::atomic<bool> stop_{false};
};

/// About the longest a block of values takes to solve between two looks at Ctrl-C (a
/// value that does not assemble can take half a millisecond).
constexpr std::chrono::microseconds kBlockTime{20'000};

/// The most a returned array may hold, with everything else a call holds: a sweep of
/// 10^7 values (kMaxValuesPerRun) of a four-bar's 266-byte rows would be 2.7 GB.
constexpr std::size_t kMaxArrayBytes = 1024 * 1024 * 1024;

/// A model as Python holds it: the engine's model (full derivation: derive() prints its
/// formulas) and the facade over that same model.
struct PyModel {
  std::shared_ptr<const kinema::Model> engine;
  kinema::MechanismModel facade;
};

/// A result keeps its model (names) alive.
struct PyResult {
  kinema::Solution solution;
  PyModel model;
};

PyModel model_of(kinema::Model model) {
  const std::shared_ptr<const kinema::Model> shared(new kinema::Model(std::move(model)), [](const kinema::Model* ended) {
    const EngineTurn turn;
    delete ended;
  });
  return PyModel{shared, kinema::EngineAccess::facade(shared)};
}

kinema::Solution solve(const PyModel& m, const Value& value) {
  if (const double* number = std::get_if<double>(&value)) return m.facade.solve(*number);
  return m.facade.solve(std::get<std::string>(value));
}

std::vector<kinema::Solution> solve_list(const PyModel& m, const std::vector<Value>& values) {
  std::vector<double> si;
  for (const Value& value : values) {
    const double* number = std::get_if<double>(&value);
    si.push_back(number ? *number : kinema::parse_input_value(m.engine->system, std::get<std::string>(value)));
  }
  return m.facade.solve(si);
}

/// m.with_parameters(b="0.31 m", c=0.09): quantities with units, or numbers in SI. Any
/// other value is an InputTypeError naming the parameter (a bare cast would say only
/// "Unable to cast Python instance of type NoneType to C++ type double", naming neither).
PyModel with_parameters(const PyModel& m, const py::kwargs& values) {
  const py::object real = py::module_::import("numbers").attr("Real");
  std::vector<std::pair<std::string, double>> si;
  for (const auto& [key, value] : values) {
    const std::string name = py::str(key);
    double number = 0;
    if (py::isinstance<py::str>(value)) {
      number = kinema::parse_parameter_value(m.engine->system, name, value.cast<std::string>());
    } else if (py::isinstance(value, real) && !py::isinstance<py::bool_>(value)) {  // True is no length
      number = value.cast<double>();
    } else {
      throw InputTypeError("with_parameters: " + name + " = " + shown(value) + " (" +
                           py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                           ") is not a number or a quantity: give a quantity with units (\"0.31 m\", \"25 deg\") "
                           "or a number in SI (0.31)");
    }
    si.emplace_back(name, number);
  }
  return model_of(kinema::with_parameters(*m.engine, si));
}

/// The output unit of each field of sweep() (the CSV's column units).
py::dict field_units(const PyModel& m) {
  const kinema::ConstraintSystem& system = m.engine->system;
  py::dict units;
  for (const kinema::ResultColumn& column : kinema::result_columns(system, kinema::OutputScale(system)))
    units[py::str(column.name)] = column.unit;
  return units;
}

py::list parameters(const PyModel& m) {
  py::list list;
  for (const kinema::SystemParameter& p : m.engine->system.parameters) {
    py::dict entry;
    entry["name"] = p.symbol.get_name();
    entry["value"] = p.value;
    entry["dimension"] = kinema::dimension_name(p.dimension);
    entry["text"] = p.text;
    list.append(entry);
  }
  return list;
}

/// result["omega3"]: a coordinate, rate or second rate by the name the file gives it.
double named(const kinema::Solution& s, const kinema::Names& names, const std::string& name) {
  const auto in = [&name](const std::vector<std::string>& list) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  if (name == names.input || in(names.unknowns)) return s.value(name);
  if (name == names.input_rate || in(names.rates)) return s.rate(name);
  if (name == names.input_second_rate || in(names.second_rates)) return s.second_rate(name);
  throw py::key_error("no coordinate, rate or second rate named \"" + name + "\"");
}

std::vector<std::string> result_names(const kinema::Names& names) {
  std::vector<std::string> all{names.input, names.input_rate, names.input_second_rate};
  for (std::size_t i = 0; i < names.unknowns.size(); ++i) {
    all.insert(all.end(), {names.unknowns[i], names.rates[i], names.second_rates[i]});
  }
  return all;
}

const char* status_name(kinema::SolutionStatus status) {
  switch (status) {
    case kinema::SolutionStatus::ok: return "ok";
    case kinema::SolutionStatus::singular: return "singular";
    default: return "unassembled";
  }
}

std::string escaped(const std::string& text) {
  return py::module_::import("html").attr("escape")(text).cast<std::string>();
}

/// A result as a table in a notebook: the input and each coordinate with its rate and
/// second rate (SI), a dash for what the status leaves unknown.
std::string result_html(const PyResult& r) {
  const kinema::Names& names = r.model.facade.names();
  const auto cell = [&](const std::string& name) {
    std::string value = "&mdash;";
    try {
      value = py::repr(py::float_(named(r.solution, names, name))).cast<std::string>();
    } catch (const kinema::Error&) {  // not known at this status: shown as a dash
    }
    return "<td>" + escaped(name) + " = " + value + "</td>";
  };
  std::string html = "<table><tr><th>value</th><th>rate</th><th>second rate</th></tr><tr>" + cell(names.input) +
                     cell(names.input_rate) + cell(names.input_second_rate) + "</tr>";
  if (!r.solution.ok()) html += "<tr><td colspan=\"3\">" + escaped(r.solution.message()) + "</td></tr>";
  for (std::size_t i = 0; i < names.unknowns.size(); ++i)
    html += "<tr>" + cell(names.unknowns[i]) + cell(names.rates[i]) + cell(names.second_rates[i]) + "</tr>";
  return html + "</table>";
}

py::tuple components(const std::array<double, 3>& v, std::size_t dimension) {
  return dimension == 3 ? py::make_tuple(v[0], v[1], v[2]) : py::make_tuple(v[0], v[1]);
}

/// "<kinema.Result theta2 = 30 deg: ok>": the input as `kinema eval` heads its block (in the
/// file's output unit, six significant digits), not in SI as the result's numbers are.
std::string result_repr(const PyResult& r) {
  const kinema::ConstraintSystem& system = r.model.engine->system;
  const kinema::OutputScale scale(system);
  return "<kinema.Result " + r.model.facade.names().input + " = " +
         kinema::format_significant(scale.input(r.solution.input())) + " " + scale.coordinate_unit(system.input.dimension) +
         ": " + status_name(r.solution.status()) + ">";
}

/// The derivation as `kinema derive --method METHOD --format FORMAT` prints it.
std::string derivation(const PyModel& m, const std::string& method, const std::string& format) {
  const kinema::Printer* printer = kinema::find_printer(kinema::PrintKind::derivation, format);
  if (!printer) throw kinema::InputError("derive: no format \"" + format + "\" (there are: text, latex)");
  const std::optional<kinema::DerivationMethod> found = kinema::find_method(method);
  if (!found) {
    throw kinema::InputError("derive: no method \"" + method +
                             "\" (there are: loops, relative-velocity, joint-coordinates)");
  }
  kinema::check_method_applies(m.engine->system, *found);
  kinema::PrintJob job{*m.engine};
  job.method = *found;
  std::ostringstream out;
  kinema::print_view(*printer, out, job);
  return out.str();
}

/// The input values from `first` to `last` by `step` ("0 deg" or numbers in SI), checked.
kinema::InputValues sweep_inputs(const PyModel& m, const Value& first, const Value& last, const Value& step) {
  const kinema::ConstraintSystem& system = m.engine->system;
  const auto written = [&](const Value& value) {
    if (const double* number = std::get_if<double>(&value)) return kinema::WrittenValue{*number, 1.0};
    return kinema::written_input_value(system, std::get<std::string>(value));
  };
  const kinema::InputValues inputs = kinema::input_sweep(system, written(first), written(last), written(step));
  kinema::check_input_range(system, inputs);
  return inputs;
}

/// A name an entry point takes as text (a column, a parameter): an InputTypeError naming
/// the argument otherwise.
std::string name_argument(const char* call, const char* argument, const py::handle& value, const char* example) {
  if (!py::isinstance<py::str>(value)) {
    throw InputTypeError(std::string(call) + ": " + argument + " = " + shown(value) + " is not a name: give it as text (" +
                         example + ")");
  }
  return value.cast<std::string>();
}

/// m.sensitivity("omega3", "b", "0 deg", "360 deg", "10 deg"): the exact derivative of a
/// column in a parameter over that sweep, SI (rad/s per m), NaN where a value is not ok;
/// the parameter's derivatives derived and compiled on the first call that asks for them
/// (then kept with the tape, for with_parameters' copies too), solved without the GIL.
/// Solved a block at a time straight into the array (the serial run solve_motion() gives, the
/// same numbers), so that memory is the array's 8 bytes a value, not a table of every
/// column (2.7 GB for 10^7 values of a four-bar), and Ctrl-C is heard between blocks.
py::array_t<double> sensitivity(const PyModel& m, const py::object& column_name, const py::object& parameter_name,
                                const Value& first, const Value& last, const Value& step) {
  const std::string column = name_argument("sensitivity", "column", column_name, "\"omega3\"");
  const std::string parameter = name_argument("sensitivity", "parameter", parameter_name, "\"b\"");
  const kinema::InputValues inputs = sweep_inputs(m, first, last, step);
  py::array_t<double> values(static_cast<py::ssize_t>(inputs.size()));
  double* out = values.mutable_data();
  std::unique_ptr<kinema::Sensitivities> derivatives;
  {
    py::gil_scoped_release unlocked;  // derived here (GiNaC), on the caller's thread as every derivation
    derivatives = std::make_unique<kinema::Sensitivities>(
        *m.engine, kinema::sensitivity_columns(m.engine->system, {column + ":" + parameter}));
  }
  Interruptible interruptible;
  interruptible.run(inputs.size(), [&] {
    kinema::SweepSettings settings;  // solve_motion()'s with its default options
    settings.rate = m.engine->system.input.rate_value;
    settings.second_rate = m.engine->system.input.second_rate_value;
    kinema::SweepSolver solver(m.engine->kinematics, inputs, settings);
    kinema::SweepBlock block;
    constexpr std::size_t kMostRows = 4096;  // a block of regular values: a few milliseconds
    std::size_t rows = kMostRows;
    while (!solver.done()) {
      interruptible.check();
      const auto started = std::chrono::steady_clock::now();
      solver.solve_next(block, rows);
      derivatives->rows(block.table, block.first, block.last, out + block.run_row, true);  // one value a row
      rows = kinema::resized_block_rows(rows, kMostRows, std::chrono::steady_clock::now() - started, kBlockTime);
    }
  });
  return values;
}

/// An empty NumPy array as the npy `header` describes it (NumPy reads the header), and what
/// the npy printer writes after the header copied into its memory as it comes: no copy of
/// a table, no second parse.
class NpyArray {
 public:
  /// `refused(rows, row_bytes, fields)` says why an array past kMaxArrayBytes is not made
  /// (it is checked before anything is held).
  NpyArray(const std::string& header,
           const std::function<std::string(std::size_t, std::size_t, std::size_t)>& refused)
      : header_size_(header.size()) {
    const py::module_ numpy = py::module_::import("numpy");
    const py::module_ format = py::module_::import("numpy.lib.format");
    const py::object stream = py::module_::import("io").attr("BytesIO")(py::bytes(header));
    const py::tuple version = format.attr("read_magic")(stream);
    const py::tuple described =
        format.attr(version[0].cast<int>() == 1 ? "read_array_header_1_0" : "read_array_header_2_0")(stream);
    const py::object dtype = numpy.attr("dtype")(described[2]);
    const std::size_t rows = described[0].cast<py::tuple>()[0].cast<std::size_t>();  // the printers' arrays are 1-D
    const std::size_t row_bytes = dtype.attr("itemsize").cast<std::size_t>();
    if (row_bytes != 0 && rows > kMaxArrayBytes / row_bytes)
      throw kinema::InputError(refused(rows, row_bytes, py::len(dtype.attr("names"))));
    array_ = numpy.attr("empty")(described[0], dtype);
    memory_ = static_cast<char*>(array_.mutable_data());
    capacity_ = static_cast<std::size_t>(array_.nbytes());
  }
  /// The printer's bytes in order, the header first (skipped); needs no GIL.
  void write(std::string_view text) {
    const std::size_t skip = at_ < header_size_ ? std::min(text.size(), header_size_ - at_) : 0;
    const std::size_t offset = at_ + skip - header_size_;
    if (offset + (text.size() - skip) > capacity_) throw std::logic_error("npy: the rows outgrow the array the header describes");
    std::memcpy(memory_ + offset, text.data() + skip, text.size() - skip);
    at_ += text.size();
  }
  /// The array, once the rows have filled it.
  py::object filled() {
    if (at_ != header_size_ + capacity_) throw std::logic_error("npy: the rows do not fill the array the header describes");
    return std::move(array_);
  }

 private:
  py::array array_;
  std::size_t header_size_, capacity_ = 0, at_ = 0;
  char* memory_ = nullptr;
};

/// The values from `first` to `last` by `step` as the program's `kinema eval --sweep ...
/// --format npy` array: the printer's rows written straight into the array's memory as
/// each block is solved and formatted (on every core, without the GIL).
py::object numpy_sweep(const PyModel& m, const Value& first, const Value& last, const Value& step) {
  const kinema::InputValues inputs = sweep_inputs(m, first, last, step);
  const kinema::ResultsPrinter& npy = *kinema::find_results_printer("npy");
  std::string header;
  npy.head(header, kinema::PrintJob{*m.engine}, inputs.size());
  NpyArray table(header, [](std::size_t rows, std::size_t row_bytes, std::size_t fields) {
    return "sweep: " + std::to_string(rows) + " values of " + std::to_string(row_bytes) + " bytes a row (" +
           std::to_string(fields) + " fields) make an array of " + kinema::format_significant(double(rows * row_bytes) / 1e9, 3) +
           " GB, more than the " + std::to_string(kMaxArrayBytes) + " bytes (1 GiB) a sweep may return: give a larger "
           "step or sweep the range in parts, or write it with `kinema eval FILE --sweep START:STOP:STEP --format npy "
           "-o FILE.npy` (streamed, any length) and read it with numpy.load(\"FILE.npy\", mmap_mode=\"r\")";
  });
  Interruptible interruptible;
  interruptible.run(inputs.size(), [&] {
    kinema::StreamSettings settings;
    settings.printer = &npy;
    settings.threads = std::max(1u, std::thread::hardware_concurrency());
    settings.write = [&](std::string_view text) { table.write(text); };
    settings.progress = [&](std::size_t, std::size_t) { interruptible.check(); };  // a block written
    settings.block_time = kBlockTime;  // blocks of slow values made smaller, that check() comes round
    kinema::stream_results(*m.engine, inputs, kinema::MotionOptions{}, settings);
  });
  return table.filled();
}

/// The program's `kinema eval --circuit STEP --format npy` array (a direction and each
/// dyad's sign a row), solved and its rows written into the array without the GIL.
py::object numpy_circuit(const PyModel& m, const std::string& step, const std::optional<Value>& start) {
  std::vector<double> inputs;
  if (start) {
    const double* number = std::get_if<double>(&*start);
    inputs.push_back(number ? *number : kinema::parse_input_value(m.engine->system, std::get<std::string>(*start)));
  }
  std::optional<kinema::Circuit> circuit;
  {
    py::gil_scoped_release unlocked;
    circuit.emplace(kinema::solve_circuit_from(*m.engine, step, inputs, {"circuit step", "circuit(\"1 deg\")", "start="}));
  }
  const kinema::ResultsPrinter& npy = *kinema::find_results_printer("npy");
  kinema::PrintJob job{*m.engine, &circuit->table};
  job.circuit = true;
  const std::size_t rows = circuit->table.size();
  std::string text;
  npy.head(text, job, rows);
  NpyArray table(text, [](std::size_t rows, std::size_t row_bytes, std::size_t fields) {  // 10^6 rows at most
    return "circuit: " + std::to_string(rows) + " rows of " + std::to_string(row_bytes) + " bytes (" +
           std::to_string(fields) + " fields), more than the " + std::to_string(kMaxArrayBytes) +
           " bytes (1 GiB) a circuit may return: give a larger step";
  });
  {
    py::gil_scoped_release unlocked;
    table.write(text);
    constexpr std::size_t kBlock = 4096;  // rows formatted at a time
    for (std::size_t first = 0; first < rows; first += kBlock) {
      text.clear();
      npy.rows(text, job, circuit->table, first, std::min(rows, first + kBlock), first);
      table.write(text);
    }
    text.clear();
    npy.tail(text, job, rows);
    table.write(text);
  }
  return table.filled();
}

/// The derivation in a notebook (Jupyter renders it with MathJax): the align* blocks of
/// `kinema derive --format latex`, each in $$...$$, without what MathJax does not read (the
/// comments, \begingroup, the structure's text).
std::string notebook_latex(const PyModel& m) {
  const std::string latex = derivation(m, "loops", "latex");
  const std::string begin = "\\begin{align*}", end = "\\end{align*}";
  std::string shown;
  for (std::size_t at = latex.find(begin); at != std::string::npos; at = latex.find(begin, at)) {
    const std::size_t stop = latex.find(end, at) + end.size();
    std::string block;
    for (std::size_t i = at; i < stop; ++i) {
      if (latex[i] == '%' && latex[i - 1] != '\\') {
        while (i < stop && latex[i] != '\n') ++i;  // a comment, to the line's end
        if (block.size() && block.back() == ' ') block.pop_back();
      }
      if (i < stop) block += latex[i];
    }
    shown += "$$" + block + "$$\n";
    at = stop;
  }
  return shown;
}

/// `kinema page FILE`'s page: the worked solution's plotting range from the file's value
/// (a turn of a crank), solved once, printed by the engine.
std::string page(const PyModel& m) {
  const kinema::ConstraintSystem& system = m.engine->system;
  const std::vector<double> values = kinema::plot_range(system, system.input.values.empty() ? 0.0 : system.input.values.front());
  kinema::check_input_range(system, values);
  std::ostringstream out;
  {
    py::gil_scoped_release unlocked;
    kinema::print_page(out, *m.engine, kinema::solve_motion(*m.engine, values), false);
  }
  return out.str();
}

/// study()'s figures=: None (all), or the field names, read once (a generator is
/// iterable once); InputTypeError for what is not a list of names.
std::optional<std::vector<std::string>> figure_names(const py::object& figures) {
  if (figures.is_none()) return std::nullopt;
  const auto refused = [&] {
    return InputTypeError("study: figures = " + shown(figures) +
                          " is not a list of field names: give figures=[\"time_ratio\", \"max_abs_omega3\"] or None");
  };
  if (py::isinstance<py::str>(figures) || py::isinstance<py::bytes>(figures) || !py::isinstance<py::iterable>(figures))
    throw refused();
  std::vector<std::string> names;
  for (const py::handle field : figures) {
    if (!py::isinstance<py::str>(field)) throw refused();
    names.push_back(field.cast<std::string>());
  }
  return names;
}

/// The figures asked for by field name (None: all); KeyError-like InputError naming the
/// fields there are.
kinema::StudyOptions study_options(const kinema::ConstraintSystem& system, const std::optional<std::vector<std::string>>& figures,
                                   std::optional<unsigned> threads) {
  kinema::StudyOptions options;
  options.threads = std::max(1u, threads.value_or(std::thread::hardware_concurrency()));
  if (!figures) return options;
  const auto fields = kinema::study_figure_fields(system);
  options.figures = 0;
  for (const std::string& wanted : *figures) {
    const auto found = std::find_if(fields.begin(), fields.end(), [&](const auto& field) { return field.first == wanted; });
    if (found == fields.end()) {
      std::string names;
      for (const auto& field : fields) names += (names.empty() ? "" : ", ") + field.first;
      throw kinema::InputError("study: no figure \"" + wanted + "\" (there are: " + names + ")");
    }
    options.figures |= kinema::study_figure_bit(found->second);
  }
  return options;
}

/// A parameter's values for study() and grid() (`call`): a NumPy array, a sequence or one
/// value of real numbers in SI, as a NumPy array of them (no copy of a NumPy array); its
/// elements, whatever its shape (numpy.meshgrid's grids), are the values. Anything else
/// (None, text, complex or bool values) is an InputTypeError naming the parameter: a bare
/// cast made None NaN, "0.1 m" a ValueError naming nothing, and kept 1+2j's real part.
py::array numbers_of(const char* call, const std::string& name, const py::handle& value) {
  const auto refused = [&](const std::string& what) {
    return InputTypeError(std::string(call) + ": " + name + " = " + what +
                          " is not a number: give numbers in SI (a NumPy array, a list or one number)");
  };
  if (value.is_none() || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) || py::isinstance<py::dict>(value))
    throw refused(shown(value));
  py::array array;
  try {
    array = py::module_::import("numpy").attr("asarray")(value);
  } catch (const py::error_already_set& e) {  // a ragged list, an object NumPy cannot read
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw refused(shown(value));
  }
  const char kind = array.dtype().kind();
  if (kind == 'f' || kind == 'i' || kind == 'u') return array;
  if (kind != 'O') throw refused(shown(value) + " (NumPy " + py::str(array.dtype()).cast<std::string>() + ")");
  return array;  // objects: each checked by column_values, after the size is
}

/// The values of numbers_of's array as doubles (its size checked by the caller first: a
/// Python loop looks at each object of an object array).
std::vector<double> column_values(const char* call, const std::string& name, const py::array& array) {
  const py::module_ numpy = py::module_::import("numpy");
  const py::object flat = numpy.attr("ravel")(array);
  if (array.dtype().kind() == 'O') {
    const py::object real = py::module_::import("numbers").attr("Real");
    std::size_t i = 0;
    for (const py::handle element : flat) {
      if (!py::isinstance(element, real) || py::isinstance<py::bool_>(element)) {  // True is no length
        throw InputTypeError(std::string(call) + ": " + name + "[" + std::to_string(i) + "] = " + shown(element) +
                             " is not a number: give numbers in SI (a NumPy array, a list or one number)");
      }
      ++i;
    }
  }
  const py::array_t<double, py::array::c_style | py::array::forcecast> column(flat);
  return std::vector<double>(column.data(), column.data() + column.size());
}

/// m.study({"b": array, "c": array}, sweep=(first, last, step), figures=None): design i is
/// (b[i], c[i]) (SI); a structured array, a row a design: the parameters, then the figures
/// (SI; "grashof" a code into GRASHOF_CLASSES), solved on every core without the GIL. The
/// designs and designs x values are bounded (check_study_size, as `--vary` is) on the
/// arrays' sizes, before any is copied.
py::object study(const PyModel& m, const py::dict& values, const std::tuple<Value, Value, Value>& sweep,
                 const py::object& figures_asked, std::optional<unsigned> threads) {
  const kinema::ConstraintSystem& system = m.engine->system;
  const py::module_ numpy = py::module_::import("numpy");
  const auto written = [&](const Value& value) {
    if (const double* number = std::get_if<double>(&value)) return kinema::WrittenValue{*number, 1.0};
    return kinema::written_input_value(system, std::get<std::string>(value));
  };
  const kinema::InputValues inputs =
      kinema::input_sweep(system, written(std::get<0>(sweep)), written(std::get<1>(sweep)), written(std::get<2>(sweep)));
  kinema::check_input_range(system, inputs);
  const std::optional<std::vector<std::string>> figures = figure_names(figures_asked);
  kinema::StudyOptions options = study_options(system, figures, threads);
  kinema::Designs designs;
  std::vector<py::array> arrays;
  std::size_t most = 0;  // the longest array: unequal lengths are refused by the study, naming them
  for (const auto& [key, value] : values) {
    designs.names.push_back(py::str(key));
    arrays.push_back(numbers_of("study", designs.names.back(), value));
    most = std::max(most, static_cast<std::size_t>(arrays.back().size()));
  }
  kinema::check_study_size(most, inputs.size(), "study");
  for (std::size_t k = 0; k < arrays.size(); ++k) designs.values.push_back(column_values("study", designs.names[k], arrays[k]));
  arrays.clear();
  Interruptible interruptible;
  options.cancelled = [&] { return interruptible.stopped(); };  // asked by every thread between its designs
  kinema::StudyResults results;
  interruptible.run(designs.size() * inputs.size(),  // at most kMaxStudyValues
                    [&] { results = kinema::run_design_study(*m.engine, designs, inputs.to_vector(), options); });
  std::vector<kinema::StudyColumn> columns;
  {
    py::gil_scoped_release unlocked;
    columns = kinema::study_columns(system, designs, results, kinema::StudyUnits::si);
  }
  // Only the figure fields asked for (a figure computes a group of them: max_rates every unknown's).
  const auto kept = [&](const kinema::StudyColumn& column, std::size_t k) {
    return k < designs.names.size() || !figures || std::find(figures->begin(), figures->end(), column.name) != figures->end();
  };
  py::list dtype;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    if (!kept(columns[k], k)) continue;
    const kinema::StudyColumn::Kind kind = columns[k].kind;
    dtype.append(py::make_tuple(columns[k].name, kind == kinema::StudyColumn::Kind::grashof ? "i1"
                                                 : kind == kinema::StudyColumn::Kind::flag  ? "?"
                                                 : kind == kinema::StudyColumn::Kind::count ? "u4"
                                                                                            : "f8"));
  }
  py::object table = numpy.attr("empty")(designs.size(), numpy.attr("dtype")(dtype));
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (kept(columns[k], k))
      table[py::str(columns[k].name)] = py::array_t<double>(columns[k].values.size(), columns[k].values.data());
  return table;
}

/// kinema.grid(b=array, c=array): every combination as study() takes them (the first name
/// slowest); refused past kMaxStudyDesigns on the axes' sizes, before any is copied.
py::dict grid(const py::kwargs& axes) {
  std::vector<std::string> names;
  std::vector<py::array> arrays;
  std::vector<std::size_t> sizes;
  for (const auto& [key, value] : axes) {
    names.push_back(py::str(key));
    arrays.push_back(numbers_of("grid", names.back(), value));
    sizes.push_back(static_cast<std::size_t>(arrays.back().size()));
  }
  kinema::design_grid_size(sizes);
  std::vector<std::vector<double>> values;
  for (std::size_t k = 0; k < arrays.size(); ++k) values.push_back(column_values("grid", names[k], arrays[k]));
  const kinema::Designs designs = kinema::design_grid(names, values);
  py::dict out;
  for (std::size_t k = 0; k < names.size(); ++k)
    out[py::str(names[k])] = py::array_t<double>(designs.values[k].size(), designs.values[k].data());
  return out;
}

}  // namespace

PYBIND11_MODULE(kinema, module) {
  module.doc() = "kinema: velocities and accelerations of mechanisms, derived symbolically and solved fast";
  // Translators are tried last registered first: the kinds after their base.
  static py::exception<kinema::Error> error(module, "Error");
  static py::exception<kinema::InputError> input_error(module, "InputError", error.ptr());
  static py::exception<kinema::UnitError> unit_error(module, "UnitError", input_error.ptr());
  static py::exception<kinema::AssemblyError> assembly_error(module, "AssemblyError", error.ptr());
  static py::exception<InputTypeError> input_type_error(module, "InputTypeError",
                                                        py::make_tuple(input_error, py::handle(PyExc_TypeError)));
  input_type_error.attr("__doc__") = "A value of a kind kinema does not take there (None, a list for a number, text for "
                                     "numbers): a kinema.InputError and a TypeError.";
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputTypeError& e) {
      input_type_error(e.what());
    } catch (const kinema::UnitError& e) {
      unit_error(e.what());
    } catch (const kinema::InputError& e) {
      input_error(e.what());
    } catch (const kinema::AssemblyError& e) {
      assembly_error(e.what());
    } catch (const kinema::Error& e) {
      error(e.what());
    }
  });

  py::class_<kinema::PointResult>(module, "Point", "A point's position, velocity and acceleration (SI).")
      .def_property_readonly("position", [](const kinema::PointResult& p) { return components(p.position, p.dimension); })
      .def_property_readonly("velocity", [](const kinema::PointResult& p) { return components(p.velocity, p.dimension); })
      .def_property_readonly("acceleration",
                             [](const kinema::PointResult& p) { return components(p.acceleration, p.dimension); })
      .def("__repr__", [](const kinema::PointResult& p) {
        return "Point(position=" + py::repr(components(p.position, p.dimension)).cast<std::string>() + ", velocity=" +
               py::repr(components(p.velocity, p.dimension)).cast<std::string>() + ", acceleration=" +
               py::repr(components(p.acceleration, p.dimension)).cast<std::string>() + ")";
      });

  py::class_<kinema::FrameResult>(module, "Frame",
                                  "A spatial chain frame's angular velocity and acceleration (SI, observer's basis).")
      .def_property_readonly("angular_velocity", [](const kinema::FrameResult& f) { return components(f.angular_velocity, 3); })
      .def_property_readonly("angular_acceleration",
                             [](const kinema::FrameResult& f) { return components(f.angular_acceleration, 3); })
      .def("__repr__", [](const kinema::FrameResult& f) {
        return "Frame(angular_velocity=" + py::repr(components(f.angular_velocity, 3)).cast<std::string>() +
               ", angular_acceleration=" + py::repr(components(f.angular_acceleration, 3)).cast<std::string>() + ")";
      });

  py::class_<PyResult>(module, "Result", "The mechanism at one input value (SI), read by name.")
      .def_property_readonly("input", py::cpp_function([](const PyResult& r) { return r.solution.input(); }, py::call_guard<EngineTurn>()))
      .def_property_readonly("status", py::cpp_function([](const PyResult& r) { return status_name(r.solution.status()); }, py::call_guard<EngineTurn>()))
      .def_property_readonly("ok", py::cpp_function([](const PyResult& r) { return r.solution.ok(); }, py::call_guard<EngineTurn>()))
      .def_property_readonly("message", py::cpp_function([](const PyResult& r) { return r.solution.message(); }, py::call_guard<EngineTurn>()))
      .def("__getitem__", [](const PyResult& r, const std::string& name) {
        return named(r.solution, r.model.facade.names(), name);
      }, py::call_guard<EngineTurn>())
      .def("keys", [](const PyResult& r) { return result_names(r.model.facade.names()); }, py::call_guard<EngineTurn>())
      .def("point", [](const PyResult& r, const std::string& name) { return r.solution.point(name); }, py::arg("name"), py::call_guard<EngineTurn>())
      .def("frame", [](const PyResult& r, const std::string& name) { return r.solution.frame(name); }, py::arg("name"),
           "A spatial chain frame's angular velocity and acceleration (rad/s, rad/s^2, observer's basis).",
           py::call_guard<EngineTurn>())
      .def("_repr_html_", &result_html, py::call_guard<EngineTurn>())
      .def("__repr__", &result_repr, py::call_guard<EngineTurn>());

  py::class_<PyModel>(module, "Model", "A mechanism read, derived and compiled once.")
      .def_property_readonly("title", py::cpp_function([](const PyModel& m) { return m.engine->system.title; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("input", py::cpp_function([](const PyModel& m) { return m.facade.names().input; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("unknowns", py::cpp_function([](const PyModel& m) { return m.facade.names().unknowns; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("rates", py::cpp_function([](const PyModel& m) { return m.facade.names().rates; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("second_rates", py::cpp_function([](const PyModel& m) { return m.facade.names().second_rates; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("points", py::cpp_function([](const PyModel& m) { return m.facade.names().points; }, py::call_guard<EngineTurn>()))
      .def_property_readonly("frames", py::cpp_function([](const PyModel& m) { return m.facade.names().frames; }, py::call_guard<EngineTurn>()),
                             "A spatial chain's frames (Result.frame reads each); empty for a planar mechanism.")
      .def_property_readonly("parameters", py::cpp_function(&parameters, py::call_guard<EngineTurn>()), "Name, SI value, dimension and text as written, in file order.")
      .def_property_readonly("units", py::cpp_function(&field_units, py::call_guard<EngineTurn>()), "The output unit of each field of sweep().")
      .def("at", [](const PyModel& m, const Value& value) { return PyResult{solve(m, value), m}; }, py::arg("value"),
           "At one input value: \"30 deg\", \"120 mm\", or a number in SI (rad, m, s).", py::call_guard<EngineTurn>())
      .def(
          "at",
          [](const PyModel& m, const std::vector<Value>& values) {
            std::vector<PyResult> results;
            for (kinema::Solution& s : solve_list(m, values)) results.push_back(PyResult{std::move(s), m});
            return results;
          },
          py::arg("values"), "At each value in order, each continued from the one before (as `kinema eval` solves a list).", py::call_guard<EngineTurn>())
      .def("derive", &derivation, py::arg("method") = "loops", py::arg("format") = "text",
           "The derivation as `kinema derive` prints it (format \"text\" or \"latex\").", py::call_guard<EngineTurn>())
      .def(
          "sweep",
          [](const PyModel& m, const Value& first, const Value& last, const Value& step) {
            return numpy_sweep(m, first, last, step);
          },
          py::arg("first"), py::arg("last"), py::arg("step"),
          "From first to last by step (\"0 deg\", \"360 deg\", \"1 deg\"; or numbers in SI): a NumPy structured array "
          "with the fields and output units of `kinema eval --format npy` (units: Model.units). The array is at most "
          "1 GiB (values x bytes a row: 4 million values of a four-bar's 266-byte rows); a longer sweep raises "
          "kinema.InputError before anything is solved: sweep it in parts, or write it with `kinema eval --sweep ... "
          "--format npy -o FILE` and numpy.load(FILE, mmap_mode=\"r\"). Ctrl-C stops it (KeyboardInterrupt).",
          py::call_guard<EngineTurn>())
      .def(
          "circuit", [](const PyModel& m, const std::string& step, const std::optional<Value>& start) {
            return numpy_circuit(m, step, start);
          },
          py::arg("step"), py::arg("start") = py::none(),
          "The whole circuit of a joints-and-links mechanism through its toggles by step (\"1 deg\"), from start (or "
          "the file's value): the structured array of `kinema eval --circuit STEP --format npy` (a direction and each "
          "dyad's sign a row).", py::call_guard<EngineTurn>())
      .def("sensitivity", &sensitivity, py::arg("column"), py::arg("parameter"), py::arg("first"), py::arg("last"),
           py::arg("step"),
           "The exact derivative of an output column (an unknown, rate, second rate, or a point's or frame's "
           "field of sweep()) in a parameter, from first to last by step as sweep() takes them: a NumPy array "
           "in SI (d omega3 / d b in rad/s per m), NaN where a value is not ok. Derived symbolically, not by "
           "differences: m.sensitivity(\"omega3\", \"b\", \"0 deg\", \"360 deg\", \"10 deg\"). Solved in blocks "
           "into the array: it holds 8 bytes a value (10^7 values at most, as sweep()). Ctrl-C stops it "
           "(KeyboardInterrupt).", py::call_guard<EngineTurn>())
      .def("with_parameters", &with_parameters,
           "The same mechanism with other parameter values, as the file edited to them: "
           "m.with_parameters(b=\"0.31 m\", delta=\"25 deg\", c=0.09) (numbers in SI). Nothing is derived or "
           "compiled again: the new model shares this one's formulas and compiled code. A value that is neither "
           "(None, a list) raises kinema.InputTypeError (an InputError and a TypeError) naming the parameter.",
           py::call_guard<EngineTurn>())
      .def("study", &study, py::arg("designs"), py::arg("sweep"), py::arg("figures") = py::none(),
           py::arg("threads") = py::none(),
           "A design study: m.study({\"b\": b, \"c\": c}, sweep=(\"0 deg\", \"360 deg\", \"1 deg\")), design i "
           "being (b[i], c[i]) in SI (kinema.grid makes every combination). Every design is solved over the sweep on "
           "this model's compiled code (nothing derived or compiled again), on every core. Returns a structured "
           "array, a row a design: the parameters, then the figures in SI (figures=None: all; else a list of "
           "field names): grashof (a code into kinema.GRASHOF_CLASSES), min_transmission_angle (rad), time_ratio, "
           "assembles, failed_values, max_abs_<rate> and max_abs_<second rate> of each unknown (max_abs_omega3, "
           "max_abs_alpha3), max_<point>_speed and max_<point>_acceleration. NaN where a figure is not defined. "
           "threads: how many threads share the designs (default: one per core). At most 10^6 designs and 10^8 "
           "values in all (designs x the sweep's values), refused with kinema.InputError before the arrays are "
           "copied; values that are not numbers (None, text, complex) raise kinema.InputTypeError naming the "
           "parameter. Ctrl-C stops it between batches of designs (KeyboardInterrupt).", py::call_guard<EngineTurn>())
      .def("page", &page, "The page `kinema page FILE` writes (one self-contained HTML file).", py::call_guard<EngineTurn>())
      .def("_repr_latex_", &notebook_latex, py::call_guard<EngineTurn>())
      .def(
          "_repr_html_",
          [](const PyModel& m) {
            // In a notebook the page runs in a frame of its own, under its own policy. Not
            // sandboxed: a sandboxed frame drew nothing in Chromium.
            const std::string html = escaped(page(m));
            return "<iframe style=\"width: 100%; height: 720px; border: 0\" srcdoc=\"" +
                   html + "\"></iframe>";
          }, py::call_guard<EngineTurn>())
      .def("__repr__", [](const PyModel& m) { return "<kinema.Model \"" + m.engine->system.title + "\">"; }, py::call_guard<EngineTurn>());

  module.def(
      "to_dataframe",
      [](const py::object& table) {
        const py::module_ pandas = py::module_::import("pandas");  // ImportError when pandas is not installed
        return pandas.attr("DataFrame")(table);
      },
      py::arg("table"), "A sweep's or a circuit's structured array as a pandas DataFrame (a column a field).");
  py::tuple classes(7);
  for (int code = 0; code < 7; ++code) classes[std::size_t(code)] = kinema::grashof_name(static_cast<kinema::GrashofClass>(code));
  module.attr("GRASHOF_CLASSES") = classes;
  module.def("grid", &grid,
             "Every combination of the values given: kinema.grid(b=[...], c=[...]) -> {\"b\": array, \"c\": array} "
             "for Model.study (the first name varies slowest). More than 10^6 combinations raise kinema.InputError "
             "before any is made.", py::call_guard<EngineTurn>());
  module.def("load", [](const std::string& path) { return model_of(kinema::load_model(path)); }, py::arg("path"),
             "Reads a mechanism file (any of the three forms).", py::call_guard<EngineTurn>());
  module.def(
      "loads",
      [](const std::string& text, const std::string& name) {
        return model_of(kinema::make_model(kinema::read_mechanism_text(text, name)));
      },
      py::arg("text"), py::arg("name") = "mechanism.toml", "The same from TOML text; name stands for the file in messages.", py::call_guard<EngineTurn>());
}
