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

#include "archive_pose.h"
#include "keyword_arguments.h"
#include "reprs.h"
#include "status_error.h"

namespace py = pybind11;

namespace {

using motifmine_python::AddPoseMethods;
using motifmine_python::Argument;
using motifmine_python::BindSkeleton;
using motifmine_python::CallbackArgument;
using motifmine_python::Check;
using motifmine_python::GivenBool;
using motifmine_python::GivenCallable;
using motifmine_python::GivenInt;
using motifmine_python::GivenStr;
using motifmine_python::GivenStrList;
using motifmine_python::OptionFailure;
using motifmine_python::SetMineKeyword;
using motifmine_python::StatusError;
using motifmine_python::SwitchArgument;
using motifmine_python::TableWholeArgument;
using motifmine_python::TextArgument;
using motifmine_python::TextListArgument;
using motifmine_python::WholeArgument;

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

// The ranges of the module's own numbers: as `motifmine words --motifs` and `motifmine search
// --top` (engine/cli/numeric_options.cc).
constexpr uint64_t kMaxWordMotifs = 65535;
constexpr uint64_t kMaxSearchTop = 100000;
constexpr uint64_t kAnyFrame = UINT64_MAX;  // checked against the clip when it is read

motifmine::MineResult Mine(const GivenStrList& inputs_given, const GivenStr& out_dir,
                           const GivenCallable& progress_given, const GivenBool& allow_older,
                           const py::kwargs& kwargs) {
  const std::vector<std::string> inputs = TextListArgument({"mine()", "inputs"}, inputs_given);
  motifmine::MineOptions options;
  options.out_dir = TextArgument({"mine()", "out_dir"}, out_dir);
  const py::object progress = CallbackArgument({"mine()", "progress"}, progress_given);
  const OlderVersions older(SwitchArgument({"mine()", "allow_older"}, allow_older));
  for (const auto& [key, value] : kwargs) SetMineKeyword(&options, key.cast<std::string>(), value);
  motifmine::MineResult result;
  Check(WithoutGil(progress, &options.progress,
                   [&] { return motifmine::Mine(inputs, options, &result); }));
  return result;
}

motifmine::MineResult Load(const GivenStr& out_dir_given) {
  const std::string out_dir = TextArgument({"load()", "out_dir"}, out_dir_given);
  motifmine::MineResult result;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::LoadMineResult(out_dir, &result);
  }
  Check(status);
  return result;
}

std::unique_ptr<motifmine::Archive> OpenArchive(const GivenStr& path,
                                                const GivenBool& allow_older) {
  const std::string checked = TextArgument({"Archive()", "path"}, path);
  const OlderVersions older(SwitchArgument({"Archive()", "allow_older"}, allow_older));
  std::unique_ptr<motifmine::Archive> archive;
  Check(motifmine::Archive::Open(checked, &archive));
  return archive;
}

py::array_t<float> Rotations(const motifmine::Archive& archive, const GivenStr& clip_given,
                             const GivenInt& start_given, const GivenInt& end_given) {
  const std::string clip = TextArgument({"rotations()", "clip"}, clip_given);
  const uint64_t start = WholeArgument({"rotations()", "start"}, start_given, 0, kAnyFrame);
  const uint64_t end = WholeArgument({"rotations()", "end"}, end_given, 0, kAnyFrame);
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

motifmine::ImportResult ImportTakes(const GivenStr& archive_given, const GivenStrList& paths_given,
                                    const GivenBool& skip_bad, const GivenInt& threads) {
  const std::string archive = TextArgument({"import_takes()", "archive"}, archive_given);
  const std::vector<std::string> paths = TextListArgument({"import_takes()", "paths"}, paths_given);
  motifmine::ImportOptions options;
  options.skip_bad = SwitchArgument({"import_takes()", "skip_bad"}, skip_bad);
  options.threads = static_cast<int>(TableWholeArgument({"import_takes()", "threads"}, threads));
  motifmine::ImportResult result;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::ImportTakes(archive, paths, options, &result);
  }
  Check(status);
  return result;
}

motifmine::WordsResult BuildWords(const GivenStr& archive_given, const GivenInt& motifs,
                                  const GivenInt& seed, const GivenInt& threads,
                                  const GivenCallable& progress_given,
                                  const GivenBool& allow_older) {
  const std::string archive = TextArgument({"build_words()", "archive"}, archive_given);
  motifmine::WordsOptions options;
  options.motifs =
      static_cast<uint32_t>(WholeArgument({"build_words()", "motifs"}, motifs, 1, kMaxWordMotifs));
  options.seed = TableWholeArgument({"build_words()", "seed"}, seed);
  options.threads = static_cast<int>(TableWholeArgument({"build_words()", "threads"}, threads));
  const py::object progress = CallbackArgument({"build_words()", "progress"}, progress_given);
  const OlderVersions older(SwitchArgument({"build_words()", "allow_older"}, allow_older));
  motifmine::WordsResult result;
  Check(WithoutGil(progress, &options.progress,
                   [&] { return motifmine::BuildWords(archive, options, &result); }));
  return result;
}

// (clip names, float64 array clips x motifs).
py::tuple Signatures(const GivenStr& archive_given, const GivenBool& allow_older) {
  const std::string archive = TextArgument({"signatures()", "archive"}, archive_given);
  const OlderVersions older(SwitchArgument({"signatures()", "allow_older"}, allow_older));
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

std::vector<motifmine::SearchMatch> Search(const GivenStr& archive_given,
                                           const GivenStr& clip_given, const GivenInt& start,
                                           const GivenInt& end, const GivenInt& top,
                                           const GivenBool& allow_older) {
  const std::string archive = TextArgument({"search()", "archive"}, archive_given);
  const std::string clip = TextArgument({"search()", "clip"}, clip_given);
  const uint64_t first = WholeArgument({"search()", "start"}, start, 0, kAnyFrame);
  const uint64_t last = WholeArgument({"search()", "end"}, end, 0, kAnyFrame);
  const auto count =
      static_cast<uint32_t>(WholeArgument({"search()", "top"}, top, 1, kMaxSearchTop));
  const OlderVersions older(SwitchArgument({"search()", "allow_older"}, allow_older));
  std::vector<motifmine::SearchMatch> matches;
  motifmine::Status status;
  {
    py::gil_scoped_release release;
    status = motifmine::SearchClipRange(archive, clip, first, last, count, &matches);
  }
  Check(status);
  return matches;
}

}  // namespace

PYBIND11_MODULE(motifmine, m) {
  const GivenBool kFalse{py::bool_(false)};
  const GivenCallable kNoCallback{py::none()};
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
      .def_readonly("fps", &motifmine::Instance::fps, "the clip's frame rate")
      .def_property_readonly("seconds", &motifmine_python::InstanceSeconds,
                             "(end - start) / fps; 0 when the rate is unknown")
      .def("__repr__", &motifmine_python::InstanceRepr);
  py::class_<motifmine::Motif>(m, "Motif")
      .def_readonly("id", &motifmine::Motif::id)
      .def_readonly("instances", &motifmine::Motif::instances)
      .def("__repr__", &motifmine_python::MotifRepr);
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
      .def_readonly("skipped_takes", &motifmine::MineResult::skipped_takes)
      .def("__repr__", &motifmine_python::MineResultRepr);
  py::class_<motifmine::ImportResult>(m, "ImportResult")
      .def_readonly("takes_imported", &motifmine::ImportResult::takes_imported)
      .def_readonly("takes_already_present", &motifmine::ImportResult::takes_already_present)
      .def_readonly("takes_mapped", &motifmine::ImportResult::takes_mapped)
      .def_readonly("frames_added", &motifmine::ImportResult::frames_added)
      .def_readonly("skipped", &motifmine::ImportResult::skipped);

  m.def("mine", &Mine, py::arg("inputs") = GivenStrList{py::list()}, py::kw_only(),
        py::arg("out_dir"), py::arg("progress") = kNoCallback, py::arg("allow_older") = kFalse,
        "Mines takes, folders or an archive (the built-in synthetic archive when `inputs` is "
        "empty) into out_dir, as `motifmine mine` does; options as keyword arguments named as "
        "the tool's flags with '_' for '-' (kmax, min_length, eps_angle, ...: "
        "motifmine.option_table() lists them), and the older k_max, eps_angle_degrees, "
        "min_length_seconds, min_length_frames and write_report. "
        "progress(stage, done, total) is called as it goes. An archive whose newest commit is "
        "damaged is refused (motifmine.Error, code 12) unless allow_older=True.");
  m.def("load", &Load, py::arg("out_dir"),
        "The MineResult of an earlier run, read back from the folder `mine` (or `motifmine mine "
        "--out`) wrote, without mining again: motifs, clips and parameters from motifs.json, "
        "timings and eps_how from run.json while it describes that motifs.json. A missing "
        "folder or one without motifs.json raises motifmine.Error (code 11) naming the path.");
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
        py::arg("skip_bad") = kFalse, py::arg("threads") = GivenInt{py::int_(0)},
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
        py::arg("motifs") = GivenInt{py::int_(words_defaults.motifs)},
        py::arg("seed") = GivenInt{py::int_(words_defaults.seed)},
        py::arg("threads") = GivenInt{py::int_(words_defaults.threads)},
        py::arg("progress") = kNoCallback, py::arg("allow_older") = kFalse,
        "The archive's motion words, their embedding, motifs and signatures, written beside it "
        "(reused when up to date), as `motifmine words` does.");
  m.def("signatures", &Signatures, py::arg("archive"), py::kw_only(),
        py::arg("allow_older") = kFalse,
        "(clip names, float64 array clips x motifs): every clip's TF-IDF signature.");
  m.def("search", &Search, py::arg("archive"), py::arg("clip"), py::arg("start"), py::arg("end"),
        py::kw_only(), py::arg("top") = GivenInt{py::int_(10)}, py::arg("allow_older") = kFalse,
        "The windows most like frames [start, end) of clip, best first: several per take, "
        "none overlapping another of its take or the query, as `motifmine search` finds them.");

  BindSkeleton(m);
  py::class_<motifmine::Archive> archive(m, "Archive");
  archive
      .def(py::init(&OpenArchive), py::arg("path"), py::kw_only(), py::arg("allow_older") = kFalse)
      .def_property_readonly("path", &motifmine::Archive::path)
      .def_property_readonly("frames", &motifmine::Archive::frames)
      .def_property_readonly("fps", &motifmine::Archive::fps)
      .def_property_readonly("clips", &motifmine::Archive::clips)
      .def_property_readonly("joint_names", &motifmine::Archive::joint_names,
                             "the archive's canonical joint names ('lfemur'); "
                             "skeleton.source_joint_names has the imported file's")
      .def("rotations", &Rotations, py::arg("clip"), py::arg("start"), py::arg("end"),
           "float32 array (frames, joints, 4): unit quaternions (w, x, y, z), each joint's "
           "relative to its parent, the root's without its heading")
      .def("__repr__", &motifmine_python::ArchiveRepr);
  AddPoseMethods(archive);
}
