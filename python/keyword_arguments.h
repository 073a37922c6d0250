// The Python functions' arguments, checked by the functions themselves so that a refusal names
// the argument. Each is taken as given (Given<kind>: any Python object, shown in the signature as
// its kind: int, str, bool, List[str], Callable) and read with a check below: a value of the
// wrong type is a TypeError, one out of its range a motifmine.OptionError (a ValueError), each
// naming the argument. (pybind11's own refusal, "incompatible function arguments", lists every
// argument instead; it is what -1 or 2^40 for a uint32_t and nan for an int gave.) Numbers the
// option table has (threads, seed, and every keyword of mine()) are read through it: its range,
// its message.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include <motifmine/motifmine.h>

namespace motifmine_python {

namespace py = pybind11;

enum class Kind { kInt, kStr, kBool, kStrList, kCallable };

template <Kind kind>
struct Given {
  py::object value;
};
using GivenInt = Given<Kind::kInt>;
using GivenStr = Given<Kind::kStr>;
using GivenBool = Given<Kind::kBool>;
using GivenStrList = Given<Kind::kStrList>;
using GivenCallable = Given<Kind::kCallable>;

// A keyword out of range on its way to Python: motifmine.OptionError, which is both a
// motifmine.Error and a ValueError.
struct OptionFailure {
  motifmine::Status status;
};

// "build_words()": the function an argument belongs to, for the messages.
struct Argument {
  const char* function;
  const char* name;
};

// A str without a NUL (text goes on to C, where a NUL would end it).
std::string TextArgument(const Argument& argument, const GivenStr& given);
// A list of such str (not a str: its characters would be taken for paths).
std::vector<std::string> TextListArgument(const Argument& argument, const GivenStrList& given);
// True or False (not 0 or 1, as for mine()'s switches).
bool SwitchArgument(const Argument& argument, const GivenBool& given);
// None or a callable.
py::object CallbackArgument(const Argument& argument, const GivenCallable& given);
// An int (not a bool) within [min, max].
uint64_t WholeArgument(const Argument& argument, const GivenInt& given, uint64_t min, uint64_t max);
// An int the option table has under the argument's name (threads, seed): its range and message.
uint64_t TableWholeArgument(const Argument& argument, const GivenInt& given);

// Sets mine()'s option `key` (the table's name with '_' for '-', or an older alias) from its
// value: TypeError for an unknown keyword (naming the nearest valid one: "did you mean
// 'kmax'?") or a value of the wrong kind, OptionFailure for one out of range, naming the keyword.
void SetMineKeyword(motifmine::MineOptions* options, const std::string& key, py::handle value);

// The signature's name of each kind.
template <Kind kind>
constexpr auto KindName() {
  using py::detail::const_name;
  if constexpr (kind == Kind::kInt) return const_name("int");
  if constexpr (kind == Kind::kStr) return const_name("str");
  if constexpr (kind == Kind::kBool) return const_name("bool");
  if constexpr (kind == Kind::kStrList) return const_name("List[str]");
  if constexpr (kind == Kind::kCallable) return const_name("Optional[Callable]");
}

}  // namespace motifmine_python

namespace pybind11::detail {

// Takes any object: the function checks it (above).
template <motifmine_python::Kind kind>
struct type_caster<motifmine_python::Given<kind>> {
  PYBIND11_TYPE_CASTER(motifmine_python::Given<kind>, motifmine_python::KindName<kind>());
  bool load(handle source, bool) {
    value.value = reinterpret_borrow<object>(source);
    return true;
  }
  static handle cast(const motifmine_python::Given<kind>& given, return_value_policy, handle) {
    return given.value.inc_ref();
  }
};

}  // namespace pybind11::detail
