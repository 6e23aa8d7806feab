// `import emoface`: the batch mapping (numpy-vectorised), the runtime Character and face
// deformation returning numpy arrays (docs/python.md). pybind11 from Debian; built with
// -DEMOFACE_PYTHON=ON.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "emoface/channels/parameters.hpp"
#include "emoface/channels/timing_io.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/weight_set.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/emotion.hpp"
#include "emoface/runtime/character.hpp"

namespace py = pybind11;
namespace rt = emoface::runtime;
namespace fx = emoface::fuzzyexpr;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// N×6 (or 6) ESV rows → checked C-contiguous doubles and the row count.
std::pair<Array, std::size_t> esv_rows(const Array& esv, bool& single) {
  if (esv.ndim() == 1 && esv.shape(0) == 6) {
    single = true;
    return {esv, 1};
  }
  if (esv.ndim() != 2 || esv.shape(1) != 6)
    throw py::value_error(
        "emotions must have shape (N, 6) or (6,): sadness happiness anger fear disgust surprise");
  single = false;
  return {esv, static_cast<std::size_t>(esv.shape(0))};
}

void check_esv(const double* e, std::size_t row) {
  for (std::size_t k = 0; k < 6; ++k)
    if (!(e[k] >= 0 && e[k] <= 1))
      throw py::value_error("row " + std::to_string(row) + ", " +
                            std::string(emoface::parlee::kBasicEmotionNames[k]) +
                            ": intensity must be in [0, 1]");
}

const fx::Engine& engine() {
  static const fx::Engine e;
  return e;
}

// kind 0: 19 muscles, 1: 35 sides, 2: 52 ARKit weights
Array map_emotions(const Array& esv, int kind) {
  bool single = false;
  auto [a, rows] = esv_rows(esv, single);
  const double* in = a.data();
  for (std::size_t r = 0; r < rows; ++r) check_esv(in + 6 * r, r);
  static const std::unique_ptr<emoface::faceweights::Mapper> arkit = [] {
    return std::make_unique<emoface::faceweights::Mapper>(
        emoface::faceweights::builtin_weight_set("arkit"),
        emoface::channels::default_parameter_names());
  }();
  const std::size_t cols = kind == 0   ? fx::kMuscleCount
                           : kind == 1 ? fx::kSideParameterCount
                                       : arkit->target_count();
  Array out(single ? std::vector<py::ssize_t>{static_cast<py::ssize_t>(cols)}
                   : std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows),
                                              static_cast<py::ssize_t>(cols)});
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    std::vector<double> params(emoface::channels::default_parameter_names().size(), 0.0);
    for (std::size_t r = 0; r < rows; ++r) {
      fx::Esv e{};
      for (std::size_t k = 0; k < 6; ++k) e[k] = in[6 * r + k];
      const fx::Fmcv f = engine().convert(e, r);
      if (kind == 0) {
        std::copy(f.begin(), f.end(), o + r * cols);
        continue;
      }
      const auto sides = fx::expand_to_sides(f);
      if (kind == 1) {
        std::copy(sides.begin(), sides.end(), o + r * cols);
        continue;
      }
      std::copy(sides.begin(), sides.end(),
                params.begin());  // the first 35 parameters are the sides
      arkit->forward(params.data(), o + r * cols);
    }
  }
  return out;
}

Array vertices_array(const emoface::facemesh::Vertices& v) {
  Array out({static_cast<py::ssize_t>(v.rows()), py::ssize_t{3}});
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array_t<int> faces_array(const emoface::facemesh::Faces& f) {
  py::array_t<int> out({static_cast<py::ssize_t>(f.rows()), py::ssize_t{3}});
  std::copy(f.data(), f.data() + f.size(), out.mutable_data());
  return out;
}

Array vector_array(const double* p, std::size_t n) {
  Array out(static_cast<py::ssize_t>(n));
  std::copy(p, p + n, out.mutable_data());
  return out;
}

std::string to_json_text(const py::object& o) {
  if (py::isinstance<py::str>(o)) return o.cast<std::string>();
  return py::module_::import("json").attr("dumps")(o).cast<std::string>();
}

// A face for deformation: the default face or a rig file.
class Face {
 public:
  explicit Face(const std::string& rig) {
    emoface::facemesh::Face f =
        rig.empty()          ? emoface::facemesh::make_default_face()
        : rig == "generic" ? emoface::facemesh::make_generic_face()
                           : emoface::facemesh::load_face(rig);
    faces_ = f.mesh.faces;
    solver_ = std::make_unique<emoface::muscles::FaceSolver>(std::move(f.mesh), std::move(f.rig));
  }
  Array neutral() const { return vertices_array(solver_->neutral().vertices); }
  py::array_t<int> faces() const { return faces_array(faces_); }
  // (42,) → (V, 3); (N, 42) → (N, V, 3)
  Array deform(const Array& params) const {
    const std::size_t np = emoface::muscles::kParameterCount;
    const bool single = params.ndim() == 1;
    if (!(single ? params.shape(0) == static_cast<py::ssize_t>(np)
                 : params.ndim() == 2 && params.shape(1) == static_cast<py::ssize_t>(np)))
      throw py::value_error(
          "parameters must have shape (42,) or (N, 42) in parameter_names() order");
    const std::size_t rows = single ? 1 : static_cast<std::size_t>(params.shape(0));
    const auto nv = static_cast<py::ssize_t>(solver_->neutral().vertices.rows());
    Array out(single ? std::vector<py::ssize_t>{nv, 3}
                     : std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows), nv, 3});
    const double* in = params.data();
    double* o = out.mutable_data();
    {
      py::gil_scoped_release release;
      emoface::muscles::Deformation d;
      emoface::muscles::DeformWorkspace ws;
      std::vector<double> v(np);
      for (std::size_t r = 0; r < rows; ++r) {
        std::copy(in + r * np, in + (r + 1) * np, v.begin());
        solver_->deform(v, d, ws);
        std::copy(d.vertices.data(), d.vertices.data() + d.vertices.size(),
                  o + r * static_cast<std::size_t>(nv) * 3);
      }
    }
    return out;
  }

 private:
  emoface::facemesh::Faces faces_;
  std::unique_ptr<emoface::muscles::FaceSolver> solver_;
};

}  // namespace

PYBIND11_MODULE(emoface, m) {
  m.doc() = "emoface: events -> emotions -> facial muscles -> animated faces (docs/python.md)";
  m.attr("__version__") = emoface::kVersion;
  py::register_exception<emoface::FormatError>(m, "FormatError", PyExc_ValueError);
  py::register_exception<emoface::IoError>(m, "IoError", PyExc_OSError);

  m.def(
      "emotion_names",
      [] {
        std::vector<std::string> n;
        for (auto s : emoface::parlee::kBasicEmotionNames) n.emplace_back(s);
        return n;
      },
      "The six emotions in ESV order.");
  m.def(
      "muscle_names", [] { return emoface::channels::muscle_names(); },
      "The 19 muscles of thesis Table 2.1.");
  m.def(
      "side_parameter_names",
      [] {
        std::vector<std::string> n;
        for (auto s : fx::side_parameter_names()) n.emplace_back(s);
        return n;
      },
      "The 35 face parameters (muscles by side).");
  m.def(
      "parameter_names", [] { return rt::Character::parameter_names(); },
      "The 42 face parameters.");
  m.def(
      "arkit_names", [] { return rt::Character::arkit_names(); }, "The 52 ARKit blend shapes.");
  m.def(
      "emotions_to_muscles", [](const Array& esv) { return map_emotions(esv, 0); },
      py::arg("emotions"),
      "(N, 6) emotion intensities in [0, 1] -> (N, 19) muscle contractions (thesis ch. 6 fuzzy "
      "rules).");
  m.def(
      "emotions_to_sides", [](const Array& esv) { return map_emotions(esv, 1); },
      py::arg("emotions"), "(N, 6) -> (N, 35) face parameters (symmetric).");
  m.def(
      "emotions_to_arkit", [](const Array& esv) { return map_emotions(esv, 2); },
      py::arg("emotions"), "(N, 6) -> (N, 52) ARKit blend-shape weights.");

  py::class_<Face>(m, "Face",
                   "A face for deformation: the default face, or a rig file (e.g. from retarget).")
      .def(py::init<const std::string&>(), py::arg("rig") = "")
      .def_property_readonly("neutral", &Face::neutral, "(V, 3) neutral vertices, metres")
      .def_property_readonly("faces", &Face::faces, "(F, 3) triangle vertex ids")
      .def("deform", &Face::deform, py::arg("parameters"),
           "(42,) -> (V, 3) or (N, 42) -> (N, V, 3) deformed vertices");

  py::class_<rt::Character>(m, "Character", "A per-frame character (docs/runtime.md).")
      .def(py::init([](const py::object& config) {
             if (config.is_none()) return std::make_unique<rt::Character>(rt::CharacterConfig{});
             return std::make_unique<rt::Character>(
                 rt::parse_character_config(to_json_text(config), "<config>"));
           }),
           py::arg("config") = py::none(),
           "config: None (defaults), a JSON string or a dict (emoface.character)")
      .def_static(
          "from_file",
          [](const std::string& path) { return rt::Character(rt::read_character_config(path)); })
      .def_static(
          "mindmotion",
          [](const std::string& graph, const std::string& map, const py::object& config) {
            rt::CharacterConfig base;
            if (!config.is_none())
              base = rt::parse_character_config(to_json_text(config), "<config>");
            return rt::Character(rt::mindmotion_config(graph, map, std::move(base)));
          },
          py::arg("graph"), py::arg("map"), py::arg("config") = py::none(),
          "a live mind-map character moved by a motion graph (docs/runtime.md): graph and map "
          "file paths; config: None, a JSON string or a dict (emoface.character without source)")
      .def_static(
          "restore",
          [](const std::string& snapshot) { return rt::restore_character(snapshot, "<snapshot>"); })
      .def(
          "push_event",
          [](rt::Character& c, const py::object& event) {
            const rt::EventResult r = c.push_event(to_json_text(event));
            return py::make_tuple(r.applied, r.message);
          },
          py::arg("event"),
          "-> (applied, message); events the model does not allow are skipped, not raised")
      .def(
          "push_stimulus",
          [](rt::Character& c, const std::string& stimulus, const py::object& weights) {
            py::dict event;
            event["stimulus"] = stimulus;
            if (!weights.is_none()) event["weights"] = weights;
            const rt::EventResult r = c.push_event(to_json_text(event));
            return py::make_tuple(r.applied, r.message);
          },
          py::arg("stimulus"), py::arg("weights") = py::none(),
          "mind-map stimulus (mindmap, mindmotion sources); weights: None or {emotion: weight}; "
          "-> (applied, message)")
      .def(
          "speak",
          [](rt::Character& c, const std::string& text) {
            double start = 0;
            c.speak(text, &start);
            return start;
          },
          py::arg("text"),
          "speaks with the espeak-ng program; returns the start time (input clock)")
      .def(
          "speak_timing",
          [](rt::Character& c, const std::string& path) {
            return c.speak(
                emoface::channels::external_utterance(emoface::channels::read_timing_file(path)));
          },
          py::arg("timing_file"),
          "speaks from external timings (emoface TSV/JSON, Rhubarb TSV/JSON)")
      .def("update", &rt::Character::update, py::arg("dt"),
           py::call_guard<py::gil_scoped_release>())
      .def_property_readonly(
          "emotions", [](const rt::Character& c) { return vector_array(c.emotions().data(), 6); })
      .def_property_readonly("parameters",
                             [](const rt::Character& c) {
                               return vector_array(c.parameters().data(), c.parameters().size());
                             })
      .def_property_readonly(
          "arkit",
          [](rt::Character& c) { return vector_array(c.arkit().data(), c.arkit().size()); })
      .def_property_readonly(
          "facs", [](rt::Character& c) { return vector_array(c.facs().data(), c.facs().size()); })
      .def("vertices", [](rt::Character& c) { return vertices_array(c.vertices()); })
      .def("faces", [](const rt::Character& c) { return faces_array(c.mesh().faces); })
      .def_property_readonly("input_time", &rt::Character::input_time)
      .def_property_readonly("output_time", &rt::Character::output_time)
      .def_property_readonly("latency", &rt::Character::latency)
      .def("snapshot", &rt::Character::snapshot);
}
