// The Python module `motifmine` (docs/python.md): the public C++ API (include/motifmine/) with
// pybind11. Long calls release the GIL; a failing Status raises motifmine.Error carrying its
// message and code; rotations come back as numpy arrays.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <motifmine/motifmine.h>

namespace py = pybind11;

namespace {

// A failed Status on its way to Python.
struct StatusError {
  motifmine::Status status;
};

void Check(const motifmine::Status& status) {
  if (!status.ok()) throw StatusError{status};
}

// A keyword out of range on its way to Python: motifmine.OptionError, which is both a
// motifmine.Error and a ValueError.
struct OptionFailure {
  motifmine::Status status;
};

// A path goes on to C as text, which ends at a NUL: a path holding one is a ValueError rather
// than another, shorter path.
const std::string& CheckPath(const std::string& path, const std::string& argument) {
  if (path.find('\0') != std::string::npos) {
    throw py::value_error(argument + " holds a NUL character, which no file name can: '" +
                          path.substr(0, path.find('\0')) + "\\0...'");
  }
  return path;
}

void CheckPaths(const std::vector<std::string>& paths, const std::string& argument) {
  for (const std::string& path : paths) CheckPath(path, argument);
}

// allow_older=True for one call: this thread may work on an archive's previous version when
// its newest commit is damaged (motifmine::AllowOlderVersions); refused otherwise.
class OlderVersions {
 public:
  explicit OlderVersions(bool allow) : before_(motifmine::AllowOlderVersions(allow)) {}
  ~OlderVersions() { motifmine::AllowOlderVersions(before_); }
  OlderVersions(const OlderVersions&) = delete;
  OlderVersions& operator=(const OlderVersions&) = delete;

 private:
  bool before_;
};

// A Python progress callback called from C++: with the GIL, and never throwing into the engine
// (the first Python error is kept and raised when the call returns).
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}
  void operator()(const std::string& stage, uint64_t done, uint64_t total) {
    py::gil_scoped_acquire gil;
    if (error_) return;
    try {
      callback_(stage, done, total);
    } catch (py::error_already_set& error) {
      error_ = std::make_shared<py::error_already_set>(std::move(error));
    }
  }
  void RaiseIfFailed() {
    if (error_) throw *error_;
  }

 private:
  py::object callback_;
  std::shared_ptr<py::error_already_set> error_;
};

using ProgressSlot = std::function<void(const std::string&, uint64_t, uint64_t)>;

// Runs `call` (returning a Status) without the GIL, with the Python callable `progress` (or None)
// installed in *slot meanwhile; a Python error the callable raised is raised once it returns.
template <typename Call>
motifmine::Status WithoutGil(const py::object& progress, ProgressSlot* slot, Call call) {
  std::optional<PythonProgress> python_progress;
  if (!progress.is_none()) {
    python_progress.emplace(progress);
    *slot = [&](const std::string& stage, uint64_t done, uint64_t total) {
      (*python_progress)(stage, done, total);
    };
  }
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = call();
  }
  *slot = nullptr;
  if (python_progress) python_progress->RaiseIfFailed();
  return status;
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

// A keyword's value as the text the option table reads: True/False for a switch, a number, or
// text ("auto", "0.5s", a path); TypeError naming the keyword for another kind of value.
std::string OptionText(const std::string& key, const std::string& type, py::handle value) {
  const bool is_bool = py::isinstance<py::bool_>(value);
  const bool is_number =
      !is_bool && (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value));
  const bool is_text = py::isinstance<py::str>(value);
  const bool textual = type == "choice" || type == "text";
  const bool may_be_text = type == "radius" || type == "groups" || type == "length";
  if (type == "switch" && is_bool) return value.cast<bool>() ? "true" : "false";
  if (type != "switch" && !textual && is_number) return py::str(value).cast<std::string>();
  if ((textual || may_be_text) && is_text) return value.cast<std::string>();
  throw py::type_error("mine(): " + key + " must be " +
                       (type == "switch" ? std::string("True or False")
                        : textual        ? std::string("a str")
                        : may_be_text    ? std::string("a number or a str")
                                         : std::string("a number")) +
                       ", not " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// Sets one option from a keyword argument through the option table; TypeError for an unknown
// keyword or a value of the wrong kind, motifmine.OptionError (code 13) for one out of range.
void SetMineOption(motifmine::MineOptions* options, const std::string& key, py::handle value) {
  // Older names the table knows as aliases that are not the option itself.
  static const std::vector<std::pair<std::string, std::string>> kTranslated = {
      {"min_length_seconds", "number"}, {"min_length_frames", "count"}, {"write_report", "switch"}};
  std::string type;
  for (const auto& [name, kind] : kTranslated) {
    if (key == name) type = kind;
  }
  if (type.empty()) {
    const std::optional<motifmine::OptionInfo> row = OptionRow(key);
    if (!row) throw py::type_error("mine() got an unexpected keyword argument '" + key + "'");
    type = row->type;
  }
  const motifmine::Status set = motifmine::SetMineOption(options, key, OptionText(key, type, value));
  if (!set.ok()) throw OptionFailure{set};
}

motifmine::MineResult Mine(const std::vector<std::string>& inputs, const std::string& out_dir,
                           const py::object& progress, bool allow_older,
                           const py::kwargs& kwargs) {
  CheckPaths(inputs, "inputs");
  motifmine::MineOptions options;
  options.out_dir = CheckPath(out_dir, "out_dir");
  for (const auto& [key, value] : kwargs) SetMineOption(&options, key.cast<std::string>(), value);
  motifmine::MineResult result;
  const OlderVersions older(allow_older);
  Check(WithoutGil(progress, &options.progress,
                   [&] { return motifmine::Mine(inputs, options, &result); }));
  return result;
}

std::unique_ptr<motifmine::Archive> OpenArchive(const std::string& path, bool allow_older) {
  std::unique_ptr<motifmine::Archive> archive;
  const OlderVersions older(allow_older);
  Check(motifmine::Archive::Open(CheckPath(path, "path"), &archive));
  return archive;
}

py::array_t<float> Rotations(const motifmine::Archive& archive, const std::string& clip,
                             uint64_t start, uint64_t end) {
  auto rotations = std::make_unique<std::vector<float>>();
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = archive.Rotations(clip, start, end, rotations.get());
  }
  Check(status);
  const py::ssize_t joints = static_cast<py::ssize_t>(archive.joint_names().size());
  const py::ssize_t frames = static_cast<py::ssize_t>(end - start);
  std::vector<float>* data = rotations.release();
  py::capsule owner(data, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>({frames, joints, py::ssize_t{4}}, data->data(), owner);
}

motifmine::ImportResult ImportTakes(const std::string& archive,
                                    const std::vector<std::string>& paths, bool skip_bad,
                                    int threads) {
  CheckPath(archive, "archive");
  CheckPaths(paths, "paths");
  motifmine::ImportOptions options;
  options.skip_bad = skip_bad;
  options.threads = threads;
  motifmine::ImportResult result;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::ImportTakes(archive, paths, options, &result);
  }
  Check(status);
  return result;
}

motifmine::WordsResult BuildWords(const std::string& archive, uint32_t motifs, uint64_t seed,
                                  int threads, const py::object& progress, bool allow_older) {
  CheckPath(archive, "archive");
  const OlderVersions older(allow_older);
  motifmine::WordsOptions options;
  options.motifs = motifs;
  options.seed = seed;
  options.threads = threads;
  motifmine::WordsResult result;
  Check(WithoutGil(progress, &options.progress,
                   [&] { return motifmine::BuildWords(archive, options, &result); }));
  return result;
}

// (clip names, float64 array clips x motifs).
py::tuple Signatures(const std::string& archive, bool allow_older) {
  CheckPath(archive, "archive");
  const OlderVersions older(allow_older);
  auto signatures = std::make_unique<motifmine::Signatures>();
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::LoadSignatures(archive, signatures.get());
  }
  Check(status);
  const py::ssize_t rows = static_cast<py::ssize_t>(signatures->clips.size());
  const py::ssize_t columns = signatures->motifs;
  py::list names;
  for (const std::string& name : signatures->clips) names.append(name);
  motifmine::Signatures* data = signatures.release();
  py::capsule owner(data, [](void* p) { delete static_cast<motifmine::Signatures*>(p); });
  return py::make_tuple(names, py::array_t<double>({rows, columns}, data->values.data(), owner));
}

std::vector<motifmine::SearchMatch> Search(const std::string& archive, const std::string& clip,
                                           uint64_t start, uint64_t end, uint32_t top,
                                           bool allow_older) {
  CheckPath(archive, "archive");
  const OlderVersions older(allow_older);
  std::vector<motifmine::SearchMatch> matches;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::SearchClipRange(archive, clip, start, end, top, &matches);
  }
  Check(status);
  return matches;
}

std::string InstanceRepr(const motifmine::Instance& instance) {
  return "Instance(clip='" + instance.clip + "', start=" + std::to_string(instance.start) +
         ", end=" + std::to_string(instance.end) + ")";
}

}  // namespace

PYBIND11_MODULE(motifmine, m) {
  m.doc() = "motifmine: motion motifs mined from motion-capture archives (docs/python.md)";

  static py::exception<StatusError> error(m, "Error", PyExc_RuntimeError);
  // Both a motifmine.Error and a ValueError; kept for the interpreter's life, as `error` is.
  static PyObject* option_error = PyErr_NewException(
      "motifmine.OptionError", py::make_tuple(error, py::handle(PyExc_ValueError)).ptr(), nullptr);
  m.attr("OptionError") = py::handle(option_error);
  py::register_exception_translator([](std::exception_ptr thrown) {
    const auto raise = [](PyObject* type, const motifmine::Status& status) {
      py::object instance = py::handle(type)(status.message());
      instance.attr("code") = static_cast<int>(status.code());
      PyErr_SetObject(type, instance.ptr());
    };
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const OptionFailure& failed) {
      raise(option_error, failed.status);
    } catch (const StatusError& failed) {
      raise(error.ptr(), failed.status);
    }
  });

  py::class_<motifmine::Instance>(m, "Instance")
      .def_readonly("clip", &motifmine::Instance::clip)
      .def_readonly("start", &motifmine::Instance::start)
      .def_readonly("end", &motifmine::Instance::end)
      .def("__repr__", &InstanceRepr);
  py::class_<motifmine::Motif>(m, "Motif")
      .def_readonly("id", &motifmine::Motif::id)
      .def_readonly("instances", &motifmine::Motif::instances)
      .def("__repr__", [](const motifmine::Motif& motif) {
        return "Motif(id=" + std::to_string(motif.id) + ", " +
               std::to_string(motif.instances.size()) + " instances)";
      });
  py::class_<motifmine::Clip>(m, "Clip")
      .def_readonly("name", &motifmine::Clip::name)
      .def_readonly("source", &motifmine::Clip::source)
      .def_readonly("first_frame", &motifmine::Clip::first_frame)
      .def_readonly("frames", &motifmine::Clip::frames)
      .def_readonly("fps", &motifmine::Clip::fps)
      .def("__repr__", [](const motifmine::Clip& clip) {
        return "Clip(name='" + clip.name + "', frames=" + std::to_string(clip.frames) + ")";
      });
  py::class_<motifmine::MineParameters>(m, "MineParameters")
      .def_readonly("eps", &motifmine::MineParameters::eps)
      .def_readonly("eps_how", &motifmine::MineParameters::eps_how)
      .def_readonly("k_max", &motifmine::MineParameters::k_max)
      .def_readonly("branch", &motifmine::MineParameters::branch)
      .def_readonly("min_length_frames", &motifmine::MineParameters::min_length_frames)
      .def_readonly("seed", &motifmine::MineParameters::seed);
  py::class_<motifmine::StageTiming>(m, "StageTiming")
      .def_readonly("stage", &motifmine::StageTiming::stage)
      .def_readonly("seconds", &motifmine::StageTiming::seconds)
      .def_readonly("reused", &motifmine::StageTiming::reused);
  py::class_<motifmine::MineResult>(m, "MineResult")
      .def_readonly("motifs", &motifmine::MineResult::motifs)
      .def_readonly("clips", &motifmine::MineResult::clips)
      .def_readonly("parameters", &motifmine::MineResult::parameters)
      .def_readonly("timings", &motifmine::MineResult::timings)
      .def_readonly("archive_path", &motifmine::MineResult::archive_path)
      .def_readonly("motifs_path", &motifmine::MineResult::motifs_path)
      .def_readonly("skipped_takes", &motifmine::MineResult::skipped_takes);
  py::class_<motifmine::ImportResult>(m, "ImportResult")
      .def_readonly("takes_imported", &motifmine::ImportResult::takes_imported)
      .def_readonly("takes_already_present", &motifmine::ImportResult::takes_already_present)
      .def_readonly("frames_added", &motifmine::ImportResult::frames_added)
      .def_readonly("skipped", &motifmine::ImportResult::skipped);

  m.def("mine", &Mine, py::arg("inputs") = std::vector<std::string>{}, py::kw_only(),
        py::arg("out_dir"), py::arg("progress") = py::none(), py::arg("allow_older") = false,
        "Mines takes, folders or an archive (the built-in synthetic archive when `inputs` is "
        "empty) into out_dir, as `motifmine mine` does; options as keyword arguments named as "
        "the tool's flags with '_' for '-' (kmax, min_length, eps_angle, ...: "
        "motifmine.option_table() lists them), and the older k_max, eps_angle_degrees, "
        "min_length_seconds, min_length_frames and write_report. "
        "progress(stage, done, total) is called as it goes. An archive whose newest commit is "
        "damaged is refused (motifmine.Error, code 12) unless allow_older=True.");
  m.def(
      "option_table",
      [] {
        py::list rows;
        for (const motifmine::OptionInfo& row : motifmine::MineOptionTable()) {
          py::dict entry;
          entry["name"] = row.name;
          entry["keyword"] = [&] {
            std::string keyword = row.name;
            std::replace(keyword.begin(), keyword.end(), '-', '_');
            return keyword;
          }();
          entry["type"] = row.type;
          entry["default"] = row.default_value;
          entry["min"] = row.min;
          entry["max"] = row.max;
          entry["min_exclusive"] = row.min_exclusive;
          entry["choices"] = row.choices;
          entry["aliases"] = row.aliases;
          entry["help"] = row.help;
          rows.append(entry);
        }
        return rows;
      },
      "Every option of mine(): a list of dicts (name, keyword, type, default, min, max, "
      "min_exclusive, choices, aliases, help), as `motifmine mine --help` lists them.");
  m.def("import_takes", &ImportTakes, py::arg("archive"), py::arg("paths"), py::kw_only(),
        py::arg("skip_bad") = false, py::arg("threads") = 0,
        "Imports BVH / ASF+AMC takes and folders into an archive (created if missing).");

  py::class_<motifmine::WordsResult>(m, "WordsResult")
      .def_readonly("takes", &motifmine::WordsResult::takes)
      .def_readonly("words", &motifmine::WordsResult::words)
      .def_readonly("motifs", &motifmine::WordsResult::motifs)
      .def_readonly("embedding_path", &motifmine::WordsResult::embedding_path)
      .def_readonly("motifs_path", &motifmine::WordsResult::motifs_path)
      .def_readonly("signatures_path", &motifmine::WordsResult::signatures_path);
  py::class_<motifmine::SearchMatch>(m, "SearchMatch")
      .def_readonly("clip", &motifmine::SearchMatch::clip)
      .def_readonly("start", &motifmine::SearchMatch::start)
      .def_readonly("end", &motifmine::SearchMatch::end)
      .def_readonly("distance", &motifmine::SearchMatch::distance)
      .def("__repr__", [](const motifmine::SearchMatch& match) {
        return "SearchMatch(clip='" + match.clip + "', start=" + std::to_string(match.start) +
               ", end=" + std::to_string(match.end) +
               ", distance=" + std::to_string(match.distance) + ")";
      });
  const motifmine::WordsOptions words_defaults;
  m.def("build_words", &BuildWords, py::arg("archive"), py::kw_only(),
        py::arg("motifs") = words_defaults.motifs, py::arg("seed") = words_defaults.seed,
        py::arg("threads") = words_defaults.threads, py::arg("progress") = py::none(),
        py::arg("allow_older") = false,
        "The archive's motion words, their embedding, motifs and signatures, written beside it "
        "(reused when up to date), as `motifmine words` does.");
  m.def("signatures", &Signatures, py::arg("archive"), py::kw_only(),
        py::arg("allow_older") = false,
        "(clip names, float64 array clips x motifs): every clip's TF-IDF signature.");
  m.def("search", &Search, py::arg("archive"), py::arg("clip"), py::arg("start"), py::arg("end"),
        py::kw_only(), py::arg("top") = 10, py::arg("allow_older") = false,
        "The takes with a window most like frames [start, end) of clip, best first, as "
        "`motifmine search` finds them.");

  py::class_<motifmine::Archive>(m, "Archive")
      .def(py::init(&OpenArchive), py::arg("path"), py::kw_only(), py::arg("allow_older") = false)
      .def_property_readonly("path", &motifmine::Archive::path)
      .def_property_readonly("frames", &motifmine::Archive::frames)
      .def_property_readonly("fps", &motifmine::Archive::fps)
      .def_property_readonly("clips", &motifmine::Archive::clips)
      .def_property_readonly("joint_names", &motifmine::Archive::joint_names)
      .def("rotations", &Rotations, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float32 array (frames, joints, 4): unit quaternions (w, x, y, z), each joint's "
           "relative to its parent, the root's without its heading");
}
