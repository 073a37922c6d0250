#include "keyword_arguments.h"

#include <algorithm>
#include <optional>
#include <utility>

namespace motifmine_python {
namespace {

std::string TypeName(py::handle value) {
  return py::str(py::type::of(value).attr("__name__")).cast<std::string>();
}

[[noreturn]] void WrongType(const Argument& argument, const std::string& wanted, py::handle value) {
  throw py::type_error(std::string(argument.function) + ": " + argument.name + " must be " +
                       wanted + ", not " + TypeName(value));
}

[[noreturn]] void OutOfRange(const std::string& name, const std::string& message) {
  throw OptionFailure{
      motifmine::Status(motifmine::Status::Code::kInvalidArgument, name + " " + message)};
}

// The option table's row for a keyword (its name with '_' for '-', or an older alias); null for
// none.
std::optional<motifmine::OptionInfo> OptionRow(const std::string& key) {
  std::string dashed = key;
  std::replace(dashed.begin(), dashed.end(), '_', '-');
  for (const motifmine::OptionInfo& row : motifmine::MineOptionTable()) {
    if (row.name == dashed) return row;
    for (const std::string& alias : row.aliases) {
      if (alias == key) return row;
    }
  }
  return std::nullopt;
}

// Older names the table knows as aliases that are not the option itself, and their kind.
const std::vector<std::pair<std::string, std::string>>& TranslatedKeywords() {
  static const std::vector<std::pair<std::string, std::string>> kTranslated = {
      {"min_length_seconds", "number"}, {"min_length_frames", "count"}, {"write_report", "switch"}};
  return kTranslated;
}

// The edit distance (insertions, deletions, substitutions) between two keywords.
size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t col = 0; col <= b.size(); ++col) row[col] = col;
  for (size_t a_idx = 1; a_idx <= a.size(); ++a_idx) {
    size_t diagonal = row[0];
    row[0] = a_idx;
    for (size_t b_idx = 1; b_idx <= b.size(); ++b_idx) {
      const size_t above = row[b_idx];
      const size_t substitute = diagonal + (a[a_idx - 1] == b[b_idx - 1] ? 0 : 1);
      row[b_idx] = std::min({above + 1, row[b_idx - 1] + 1, substitute});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The valid keyword nearest `key` (the table's keywords first, then their aliases and the older
// names, then `others`), or "" when none is near enough to be a slip.
std::string ClosestKeyword(const std::string& key, const std::vector<std::string>& others) {
  std::vector<std::string> candidates;
  for (const motifmine::OptionInfo& row : motifmine::MineOptionTable()) {
    std::string keyword = row.name;
    std::replace(keyword.begin(), keyword.end(), '-', '_');
    candidates.push_back(keyword);
  }
  for (const motifmine::OptionInfo& row : motifmine::MineOptionTable()) {
    candidates.insert(candidates.end(), row.aliases.begin(), row.aliases.end());
  }
  for (const auto& [name, kind] : TranslatedKeywords()) candidates.push_back(name);
  candidates.insert(candidates.end(), others.begin(), others.end());
  std::string best;
  size_t best_distance = std::max<size_t>(2, key.size() / 3) + 1;  // farther: not a slip
  for (const std::string& candidate : candidates) {
    const size_t distance = EditDistance(key, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

// TypeError for a keyword no option has, naming the nearest one.
[[noreturn]] void UnknownKeyword(const Argument& argument, const std::vector<std::string>& others) {
  const std::string key = argument.name;
  const std::string closest = ClosestKeyword(key, others);
  throw py::type_error(std::string(argument.function) + ": unknown keyword '" + key + "'" +
                       (closest.empty() ? std::string(" (motifmine.option_table() lists them)")
                                        : ": did you mean '" + closest + "'?"));
}

// A keyword's value as the text the option table reads: True/False for a switch, a number, or
// text ("auto", "0.5s", a path); TypeError naming the keyword for another kind of value.
std::string OptionText(const Argument& argument, const std::string& type, py::handle value) {
  const bool is_bool = py::isinstance<py::bool_>(value);
  const bool is_number =
      !is_bool && (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value));
  const bool is_text = py::isinstance<py::str>(value);
  const bool textual = type == "choice" || type == "text";
  const bool may_be_text = type == "radius" || type == "groups" || type == "length";
  if (type == "switch" && is_bool) return value.cast<bool>() ? "true" : "false";
  if (type != "switch" && !textual && is_number) return py::str(value).cast<std::string>();
  if ((textual || may_be_text) && is_text) return value.cast<std::string>();
  WrongType(argument,
            type == "switch" ? "True or False"
            : textual        ? "a str"
            : may_be_text    ? "a number or a str"
                             : "a number",
            value);
}

// The table's message names the option ("eps-angle must be ..."): name the keyword given.
motifmine::Status NamingTheKeyword(const motifmine::Status& status, const std::string& option,
                                   const std::string& key) {
  const std::string& message = status.message();
  if (key == option || message.rfind(option + " ", 0) != 0) return status;
  return motifmine::Status(status.code(), key + message.substr(option.size()));
}

// Sets the table's option named by `argument` (or an older alias) from its value; an unknown
// one is a TypeError naming the nearest of the table's keywords and `others`.
void SetTableKeyword(motifmine::MineOptions* options, const Argument& argument, py::handle value,
                     const std::vector<std::string>& others = {}) {
  const std::string key = argument.name;
  std::string type;
  for (const auto& [name, kind] : TranslatedKeywords()) {
    if (key == name) type = kind;
  }
  std::string option = key;
  if (type.empty()) {
    const std::optional<motifmine::OptionInfo> row = OptionRow(key);
    if (!row) UnknownKeyword(argument, others);
    type = row->type;
    option = row->name;
  }
  const motifmine::Status set =
      motifmine::SetMineOption(options, key, OptionText(argument, type, value));
  if (!set.ok()) throw OptionFailure{NamingTheKeyword(set, option, key)};
}

}  // namespace

std::string TextArgument(const Argument& argument, const GivenStr& given) {
  if (!py::isinstance<py::str>(given.value)) WrongType(argument, "a str", given.value);
  const std::string text = given.value.cast<std::string>();
  if (text.find('\0') != std::string::npos) {
    throw py::value_error(std::string(argument.name) +
                          " holds a NUL character, which no file name can: '" +
                          text.substr(0, text.find('\0')) + "\\0...'");
  }
  return text;
}

std::vector<std::string> TextListArgument(const Argument& argument, const GivenStrList& given) {
  if (py::isinstance<py::str>(given.value) || !py::isinstance<py::sequence>(given.value)) {
    WrongType(argument, "a list of str", given.value);
  }
  std::vector<std::string> texts;
  for (py::handle item : given.value) {
    if (!py::isinstance<py::str>(item)) WrongType(argument, "a list of str", item);
    texts.push_back(TextArgument(argument, GivenStr{py::reinterpret_borrow<py::object>(item)}));
  }
  return texts;
}

bool SwitchArgument(const Argument& argument, const GivenBool& given) {
  if (!py::isinstance<py::bool_>(given.value)) WrongType(argument, "True or False", given.value);
  return given.value.cast<bool>();
}

py::object CallbackArgument(const Argument& argument, const GivenCallable& given) {
  if (!given.value.is_none() && !PyCallable_Check(given.value.ptr())) {
    WrongType(argument, "None or a callable (stage, done, total)", given.value);
  }
  return given.value;
}

uint64_t WholeArgument(const Argument& argument, const GivenInt& given, uint64_t min,
                       uint64_t max) {
  const py::handle value = given.value;
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value)) {
    WrongType(argument, "an int", value);
  }
  const py::int_ low(min);
  const py::int_ high(max);
  if (value < low || value > high) {
    OutOfRange(argument.name, "must be a whole number in [" + std::to_string(min) + ", " +
                                  std::to_string(max) + "], not " +
                                  py::repr(value).cast<std::string>());
  }
  return value.cast<uint64_t>();
}

uint64_t TableWholeArgument(const Argument& argument, const GivenInt& given) {
  motifmine::MineOptions scratch;
  SetTableKeyword(&scratch, argument, given.value);
  return std::stoull(motifmine::GetMineOption(scratch, argument.name));
}

void SetMineKeyword(motifmine::MineOptions* options, const std::string& key, py::handle value) {
  // mine()'s own arguments, for a slip in one of them (it reaches **kwargs).
  static const std::vector<std::string> kMineArguments = {"inputs", "out_dir", "progress",
                                                          "allow_older"};
  SetTableKeyword(options, {"mine()", key.c_str()}, value, kMineArguments);
}

}  // namespace motifmine_python
