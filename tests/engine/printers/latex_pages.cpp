#include "engine/printers/latex_pages.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/run/view.hpp"
#include "engine/symbolic/dyad_method.hpp"

#include "tests/test_support.hpp"

namespace kinema_test {
namespace {

std::filesystem::path latex_directory() {
  const auto directory = kinema_test::scratch_directory() / "latex";
  std::filesystem::create_directories(directory);
  return directory;
}

bool starts_with(const std::string& text, const std::string& start) { return text.rfind(start, 0) == 0; }

// A line that opens a figure's box rather than saying anything: what stands between a
// figure's drawing and the text before it.
bool opens_figure(const std::string& line) {
  return line.empty() || line == "\\begin{center}" || line == "\\medskip" || line == "{\\centering\\noindent" ||
         starts_with(line, "\\tdplotsetmaincoords") || starts_with(line, "\\par\\nopagebreak") ||
         line.find("\\begin{minipage}") != std::string::npos;
}

// The line that closes a figure's box (after its caption).
bool closes_figure(const std::string& line) {
  return line == "\\end{minipage}" || line == "\\end{center}" || line == "}\\par\\medskip";
}

}  // namespace

int compile_document(const std::string& tex_text, const std::string& name, std::string& log) {
  const auto directory = latex_directory();
  std::ofstream(directory / (name + ".tex")) << tex_text;
  std::filesystem::remove(directory / (name + ".pdf"));
  const std::string command = "cd '" + directory.string() + "' && pdflatex -interaction=batchmode -halt-on-error '" +
                              name + ".tex' > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  log = read_file((directory / (name + ".log")).string());
  if (status != 0 || log.find("Undefined control sequence") != std::string::npos) return 0;
  const std::string info = (directory / (name + ".info")).string();
  std::system(("pdfinfo '" + (directory / (name + ".pdf")).string() + "' > '" + info + "' 2>/dev/null").c_str());
  const std::string text = read_file(info);
  const auto at = text.find("Pages:");
  return at == std::string::npos ? 0 : std::stoi(text.substr(at + 6));
}

std::vector<double> text_heights(const std::string& name) {
  const auto directory = latex_directory();
  const std::string boxes = (directory / (name + ".bbox")).string();
  std::system(("pdftotext -bbox '" + (directory / (name + ".pdf")).string() + "' '" + boxes + "' 2>/dev/null").c_str());
  const std::string text = read_file(boxes);
  std::vector<double> heights;
  for (auto page = text.find("<page "); page != std::string::npos; page = text.find("<page ", page + 1)) {
    const auto end = text.find("</page>", page);
    const double height = std::stod(text.substr(text.find("height=\"", page) + 8));
    double top = height, bottom = 0;
    for (auto word = text.find("<word ", page); word < end; word = text.find("<word ", word + 1)) {
      const double y_min = std::stod(text.substr(text.find("yMin=\"", word) + 6));
      const double y_max = std::stod(text.substr(text.find("yMax=\"", word) + 6));
      if (y_min > height - 80) continue;  // the page number
      top = std::min(top, y_min);
      bottom = std::max(bottom, y_max);
    }
    heights.push_back(bottom > top ? (bottom - top) / height : 0);
  }
  return heights;
}

std::vector<Overfull> overfull_boxes(const std::string& log) {
  std::vector<Overfull> found;
  for (auto at = log.find("Overfull \\"); at != std::string::npos; at = log.find("Overfull \\", at + 1)) {
    const std::string text = log.substr(at, log.find('\n', at) - at);
    const double points = std::atof(text.c_str() + text.find('(') + 1);
    const auto line_at = text.find("line");
    const std::size_t line = line_at == std::string::npos ? 0 : std::strtoul(text.c_str() + text.find_first_of("0123456789", line_at), nullptr, 10);
    if (points > 1.0) found.push_back({points, line, text});
  }
  return found;
}

MarkedFigures mark_figures(const std::string& tex) {
  std::vector<std::string> lines;
  std::istringstream in(tex);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  MarkedFigures marked;
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (starts_with(lines[i], "\\begin{tikzpicture}")) starts.push_back(i);
  const std::string caption = "Figure~\\thefigure: ";
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const std::string key = std::to_string(k + 1);
    // The caption: between this drawing and the next.
    bool captioned = false;
    const std::size_t next = k + 1 < starts.size() ? starts[k + 1] : lines.size();
    for (std::size_t i = starts[k]; i < next && !captioned; ++i) {
      const auto at = lines[i].find(caption);
      if (at == std::string::npos) continue;
      lines[i].insert(at + caption.size() - 1, "\\label{kinema-caption-" + key + "}");
      captioned = true;
    }
    // What comes before the drawing, past the lines that open its box.
    std::size_t before = starts[k];
    while (before > 0 && opens_figure(lines[before - 1])) --before;
    std::string& line = lines[before > 0 ? before - 1 : 0];
    const bool after_figure = closes_figure(line);
    // A display or a table before it: nothing introduces the figure (no label; the check fails).
    const bool introduced = !after_figure && !starts_with(line, "\\end{") && !starts_with(line, "\\bottomrule");
    const std::string label = "\\label{kinema-intro-" + key + "}";
    if (introduced && (starts_with(line, "\\subsection*{") || starts_with(line, "\\subsubsection*{")))
      line.insert(line.rfind('}'), label);  // in the heading's text
    else if (introduced)
      line += label;  // after the sentence's last word
    marked.captioned.push_back(captioned);
    marked.follows_figure.push_back(after_figure);
    marked.before.push_back(line);
    lines[starts[k]] = "\\leavevmode\\label{kinema-figure-" + key + "}" + lines[starts[k]];
  }
  marked.figures = starts.size();
  for (const std::string& line : lines) marked.tex += line + "\n";
  return marked;
}

std::map<std::string, int> label_pages(const std::string& name) {
  const std::string aux = read_file((latex_directory() / (name + ".aux")).string());
  std::map<std::string, int> pages;
  const std::string start = "\\newlabel{";
  for (auto at = aux.find(start); at != std::string::npos; at = aux.find(start, at + 1)) {
    const auto key_end = aux.find('}', at);
    // {{label}{page}}: past the label's group (it may hold braces) to the page's.
    std::size_t i = key_end + 2, depth = 0;
    do {
      depth += aux[i] == '{';
      depth -= aux[i] == '}';
      ++i;
    } while (depth > 0 && i < aux.size());
    pages[aux.substr(at + start.size(), key_end - at - start.size())] = std::atoi(aux.c_str() + i + 1);
  }
  return pages;
}

void check_layout(const std::string& name, const MarkedFigures& marked, int pages, const std::string& log) {
  CAPTURE(name);
  // No near-empty page (issue 32): every page but the last has text over a quarter of its height.
  const std::vector<double> heights = text_heights(name);
  CHECK(static_cast<int>(heights.size()) == pages);
  for (std::size_t page = 0; page + 1 < heights.size(); ++page) {
    CAPTURE(page + 1);
    CHECK(heights[page] >= 0.25);
  }
  // Each figure on its caption's page and on the page of the heading or sentence before it.
  std::map<std::string, int> labels = label_pages(name);
  CHECK(marked.figures > 0);
  for (std::size_t k = 0; k < marked.figures; ++k) {
    const std::string key = std::to_string(k + 1);
    CAPTURE(key);
    INFO("after: " << marked.before[k]);
    const int page = labels["kinema-figure-" + key];
    CHECK(page > 0);
    CHECK(marked.captioned[k]);
    CHECK(labels["kinema-caption-" + key] == page);
    if (!marked.follows_figure[k]) CHECK(labels["kinema-intro-" + key] == page);
  }
  // Nothing runs into the margin: no overfull line wider than 1 pt (issue 13).
  for (const Overfull& box : overfull_boxes(log)) {
    INFO(box.text);
    CHECK(box.points <= 1.0);
  }
}

std::string worked_solution_sparse_plots(const kinema::Model& model, kinema::DerivationMethod method,
                                         const std::vector<double>& inputs) {
  const kinema::MotionTable values = kinema::solve_motion(model, inputs);
  const std::vector<double> range = kinema::plot_range(model.system, inputs.front());
  std::vector<double> sparse;
  for (std::size_t k = 0; k < range.size(); k += 6) sparse.push_back(range[k]);
  if (sparse.back() != range.back()) sparse.push_back(range.back());  // the run's last value kept
  const kinema::MotionTable sweep = kinema::solve_motion(model, sparse);
  kinema::PrintJob job{model, &values, &sweep};
  job.method = method;
  std::ostringstream out;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::document, "latex"), out, job);
  return out.str();
}

std::vector<kinema::DerivationMethod> methods_of(const kinema::Model& model) {
  std::vector<kinema::DerivationMethod> methods = {kinema::DerivationMethod::loops};
  for (kinema::DerivationMethod m : {kinema::DerivationMethod::relative_velocity, kinema::DerivationMethod::joint_coordinates}) {
    try {
      kinema::check_method_applies(model.system, m);
      methods.push_back(m);
    } catch (const kinema::InputError&) {
    }
  }
  return methods;
}

}  // namespace kinema_test
