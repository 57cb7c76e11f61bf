#include "readers/class_table.hpp"

#include <cmath>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/base/user_text.hpp"
#include "readers/file_reader.hpp"

namespace kinema {

namespace {

using nlohmann::json;

constexpr std::size_t kMaxClassTableBytes = 16 * 1024 * 1024;

// Reads one class.json, every message naming the file and where in it.
class ClassTableReader {
 public:
  explicit ClassTableReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(path_ + ": " + where + ": " + what + " (the class table kinema problems writes: docs/check.md)");
  }

  const json& member(const json& object, const char* key, const std::string& where) const {
    if (!object.is_object() || !object.contains(key)) fail(where, std::string("no \"") + key + "\"");
    return object.at(key);
  }

  std::string text(const json& value, const std::string& where) const {
    if (value.is_string()) return value.get<std::string>();
    if (value.is_number()) return value.dump();
    fail(where, "expected a string");
  }

  double number(const json& value, const std::string& where) const {
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(where, "expected a finite number");
    return value.get<double>();
  }

  // A unit kinema reads ("m", "rpm", "deg"), or none: the table's text reaches reports
  // and messages, so nothing else is taken from it.
  std::string unit(const json& value, const std::string& where) const {
    const std::string written = text(value, where);
    if (written.empty()) return written;
    try {
      parse_quantity("1 " + written);
    } catch (const Error&) {
      fail(where, "\"" + one_line(written) + "\" is not a unit kinema reads (" + understood_units() + ")");
    }
    return written;
  }

  long whole_number(const json& value, const std::string& where) const {
    if (!value.is_number_integer()) fail(where, "expected a whole number");
    return value.get<long>();
  }

  std::optional<AnswerTolerance> tolerance(const json& root) const {
    if (!root.contains("tolerance")) return std::nullopt;
    const json& t = root.at("tolerance");
    if (t.is_object() && t.contains("relative")) {
      const double relative = number(t.at("relative"), "tolerance.relative");
      if (!(relative > 0 && relative < 1)) fail("tolerance.relative", "a fraction between 0 and 1");
      AnswerTolerance tolerance;
      tolerance.relative = relative;
      return tolerance;
    }
    if (t.is_object() && t.contains("sig_figs")) {
      return significant_figures(whole_number(t.at("sig_figs"), "tolerance.sig_figs"), path_ + ": tolerance.sig_figs");
    }
    fail("tolerance", "expected {\"relative\": 0.01} or {\"sig_figs\": 3}");
  }

  ClassVariant variant(const json& entry, const std::string& where) const {
    ClassVariant variant;
    variant.number = whole_number(member(entry, "variant", where), where + ".variant");
    const std::string named = "variant " + std::to_string(variant.number);
    if (entry.contains("parameters")) {
      const json& parameters = entry.at("parameters");
      if (!parameters.is_object()) fail(named + ".parameters", "expected an object of parameters");
      for (const auto& [name, value] : parameters.items()) {
        const std::string at = named + ".parameters." + name;
        ClassParameter p{name, number(member(value, "si", at), at + ".si"), "", ""};
        if (value.contains("value")) p.value = text(value.at("value"), at + ".value");
        if (value.contains("unit")) p.unit = unit(value.at("unit"), at + ".unit");
        variant.parameters.push_back(std::move(p));
      }
    }
    if (entry.contains("answers")) {
      const json& answers = entry.at("answers");
      if (!answers.is_array()) fail(named + ".answers", "expected an array");
      for (std::size_t i = 0; i < answers.size(); ++i) {
        const std::string at = named + ".answers[" + std::to_string(i) + "]";
        ClassAnswer answer;
        answer.quantity = text(member(answers[i], "quantity", at), at + ".quantity");
        if (answers[i].contains("at")) answer.at = text(answers[i].at("at"), at + ".at");
        if (answers[i].contains("at_si")) answer.at_si = number(answers[i].at("at_si"), at + ".at_si");
        variant.answers.push_back(std::move(answer));
      }
    }
    return variant;
  }

  ClassTable read(const std::string& content) const {
    json root;
    try {
      root = json::parse(content);
    } catch (const json::parse_error& error) {
      throw InputError(path_ + ": not a class table (JSON): " + one_line(error.what()));
    }
    ClassTable table;
    table.path = path_;
    const std::filesystem::path source = text(member(root, "source", "the top level"), "source");
    table.source = source.is_absolute() ? source.string() : (std::filesystem::path(path_).parent_path() / source).string();
    table.tolerance = tolerance(root);
    const json& variants = member(root, "variants", "the top level");
    if (!variants.is_array() || variants.empty()) fail("variants", "expected an array of variants");
    std::set<long> numbers;
    for (std::size_t i = 0; i < variants.size(); ++i) {
      const std::string where = "variants[" + std::to_string(i) + "]";
      table.variants.push_back(variant(variants[i], where));
      if (!numbers.insert(table.variants.back().number).second)
        fail(where + ".variant", "variant " + std::to_string(table.variants.back().number) +
                                     " is given twice; each variant has one number");
    }
    return table;
  }

 private:
  std::string path_;
};

}  // namespace

ClassTable read_class_table_text(const std::string& text, const std::string& path) {
  return ClassTableReader(path).read(text);
}

ClassTable read_class_table(const std::string& path) {
  return read_class_table_text(reading::read_text_file(path, kMaxClassTableBytes, "class table"), path);
}

const ClassVariant& class_variant(const ClassTable& table, long number) {
  for (const ClassVariant& variant : table.variants)
    if (variant.number == number) return variant;
  std::string numbers;
  for (const ClassVariant& variant : table.variants) numbers += (numbers.empty() ? "" : ", ") + std::to_string(variant.number);
  if (table.variants.size() > 20) {
    numbers = std::to_string(table.variants.front().number) + " ... " + std::to_string(table.variants.back().number);
  }
  throw InputError(table.path + ": no variant " + std::to_string(number) + "; the class table has variants " + numbers);
}

}  // namespace kinema
