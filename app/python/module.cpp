// `import simsols`: the solver from Python (pybind11), the same library the
// simsols executable uses.
//
//   scene = simsols.load_scene("assets/scenes/shear_box.toml")
//   d = scene.to_dict(); d["time_step"]["fraction"] = 0.2
//   scene = simsols.scene_from_dict(d, name="edited")   # validated as a TOML file
//   sim = simsols.Simulation(scene)
//   sim.advance(1000)                                   # the GIL is released
//   x = sim.positions()                                 # (N, 3) float64, m
//   sim.save_checkpoint("c.bin"); sim = simsols.load_checkpoint("c.bin")
//   r = simsols.run_test(scene, "out")   # as `simsols run`: r["summary"], r["rows"]
//   s = simsols.study_sensitivity("out", preset="ci")   # as `simsols study sensitivity`
//   c = simsols.calibrate("kfs.toml", "out")           # as `simsols calibrate`
//   p = simsols.predict("pred.toml", "out")            # as `simsols predict`
//
// Design:
// - Scenes travel as TOML. A dict becomes TOML text (toml++) and goes
//   through the loader, so a scene built in Python is checked by the same
//   code, with the same messages (file, field, allowed range), as a file;
//   to_dict() is the loader's own output (to_toml) read back.
// - Arrays come from one download of the device state (Simulation::snapshot)
//   and own their buffer: no copy per element, no copy after the download.
// - Errors: SceneError (a ValueError) carries file, line, field, code and
//   every problem; RunawayError (a RuntimeError) a step that went wrong;
//   DeviceError the OpenCL runtime's.
// - No module state: a Device is opened per Simulation unless one is passed.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "app/experiment/apparatus_run.h"
#include "app/experiment/calibration/calibration_report.h"
#include "app/experiment/calibration/prediction.h"
#include "solver/apparatus/registry.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/shear_box/sensitivity.h"
#include "app/experiment/shear_box/shear_run.h"
#include "solver/common/errors.h"
#include "solver/core/engine_options.h"
#include "solver/core/guard.h"
#include "solver/core/simulation.h"
#include "solver/io/checkpoint.h"
#include "solver/io/scene_toml.h"

namespace py = pybind11;

namespace simsols::python {
namespace {

// ----------------------------------------------------------- TOML <-> Python

py::object to_python(const toml::node& n);

py::object to_python(const toml::table& t) {
  py::dict d;
  for (const auto& [key, value] : t) d[py::str(std::string(key.str()))] = to_python(value);
  return d;
}

py::object to_python(const toml::node& n) {
  if (const auto* t = n.as_table()) return to_python(*t);
  if (const auto* a = n.as_array()) {
    py::list l;
    for (const toml::node& e : *a) l.append(to_python(e));
    return l;
  }
  if (const auto* s = n.as_string()) return py::str(s->get());
  if (const auto* i = n.as_integer()) return py::int_(i->get());
  if (const auto* f = n.as_floating_point()) return py::float_(f->get());
  if (const auto* b = n.as_boolean()) return py::bool_(b->get());
  throw std::invalid_argument("a TOML date or time has no place in a scene");
}

// A Python value as a TOML node; `where` names it in messages ("scene.x").
std::unique_ptr<toml::node> to_toml_node(py::handle v, const std::string& where);

toml::table to_toml_table(const py::dict& d, const std::string& where) {
  toml::table t;
  for (auto [k, v] : d) {
    if (!py::isinstance<py::str>(k))
      throw py::type_error(where + ": keys must be strings, not " + std::string(py::str(k.get_type())));
    const std::string key = k.cast<std::string>();
    t.insert(key, std::move(*to_toml_node(v, where.empty() ? key : where + "." + key)));
  }
  return t;
}

std::unique_ptr<toml::node> to_toml_node(py::handle v, const std::string& where) {
  if (py::isinstance<py::bool_>(v)) return std::make_unique<toml::value<bool>>(v.cast<bool>());
  if (py::isinstance<py::int_>(v)) {
    const long long i = PyLong_AsLongLong(v.ptr());
    if (i == -1 && PyErr_Occurred()) {
      PyErr_Clear();
      throw py::value_error(where + ": " + std::string(py::str(v)) + " does not fit a 64-bit integer");
    }
    return std::make_unique<toml::value<std::int64_t>>(std::int64_t(i));
  }
  if (py::isinstance<py::float_>(v)) return std::make_unique<toml::value<double>>(v.cast<double>());
  if (py::isinstance<py::str>(v)) return std::make_unique<toml::value<std::string>>(v.cast<std::string>());
  // other numbers (NumPy's int64, float32, ...): integers by __index__, the rest by __float__
  if (PyIndex_Check(v.ptr())) return to_toml_node(py::int_(py::reinterpret_borrow<py::object>(v)), where);
  if (py::hasattr(v, "__float__")) return std::make_unique<toml::value<double>>(py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>());
  if (py::isinstance<py::dict>(v)) return std::make_unique<toml::table>(to_toml_table(v.cast<py::dict>(), where));
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    auto a = std::make_unique<toml::array>();
    int k = 0;
    for (py::handle e : v) a->push_back(std::move(*to_toml_node(e, where + "[" + std::to_string(k++) + "]")));
    return a;
  }
  throw py::type_error(where + ": " + std::string(py::str(v.get_type())) +
                       " is not a TOML value (bool, int, float, str, list, dict)");
}

Scene scene_from_dict(const py::dict& d, const std::string& name) {
  std::ostringstream text;
  text << to_toml_table(d, "");
  return parse_scene(text.str(), name);
}

py::dict scene_to_dict(const Scene& scene) {
  return to_python(toml::parse(to_toml(scene))).cast<py::dict>();
}

// ------------------------------------------------------------------- arrays

// An array of T that owns `v` (moved in, no copy): its elements E read as
// `columns` values of T each, so n x columns (one column: a vector).
template <typename T, typename E>
py::array_t<T> owning_array(std::vector<E>&& v, py::ssize_t columns) {
  static_assert(sizeof(E) % sizeof(T) == 0);
  auto* owned = new std::vector<E>(std::move(v));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<E>*>(p); });
  T* data = reinterpret_cast<T*>(owned->data());
  const auto rows = py::ssize_t(owned->size() * sizeof(E) / sizeof(T)) / columns;
  if (columns == 1) return py::array_t<T>({rows}, {py::ssize_t(sizeof(T))}, data, free);
  return py::array_t<T>({rows, columns}, {py::ssize_t(columns * sizeof(T)), py::ssize_t(sizeof(T))},
                        data, free);
}

// (n, 3) float64
py::array_t<double> vec3_array(std::vector<Vec3>&& v) { return owning_array<double>(std::move(v), 3); }

template <typename T>
py::array_t<T> vector_array(std::vector<T>&& v) {
  return owning_array<T>(std::move(v), 1);
}

// Every touching contact: (pairs (m, 2) int32: a, b with b = -1 - wall for
// a wall), forces (m, 3) float64 in N, what b exerts on a.
py::tuple contacts_arrays(Simulation& sim) {
  std::vector<ContactForce> c = sim.contacts();
  std::vector<int> pairs;
  std::vector<Vec3> forces;
  pairs.reserve(2 * c.size());
  forces.reserve(c.size());
  for (const ContactForce& f : c) {
    pairs.push_back(f.a);
    pairs.push_back(f.b);
    forces.push_back(f.force);
  }
  return py::make_tuple(owning_array<int>(std::move(pairs), 2), vec3_array(std::move(forces)));
}

std::shared_ptr<Device> device_or_open(std::shared_ptr<Device> device) {
  return device ? device : Device::open(engine_options_from_environment());
}

// ------------------------------------------------------------ the apparatus

// A CSV with a header line (the rows files: shear.csv, ...) as one float64
// array per column, named as in the file (units in the names).
// The walls now, one dict each: name, point (m), normal, velocity (m/s),
// the force the beads exert on it (N), its contacts; `apparatus` names the
// apparatus it belongs to ("" for the scene's own walls).
py::list walls_list(Simulation& sim) {
  const Scene& scene = sim.scene();
  const std::vector<WallReaction> reactions = sim.wall_reactions();
  const ApparatusKind* kind = apparatus_kind(scene);
  const int first = kind ? scene.cell()->first_wall : 0, last = kind ? first + kind->walls : 0;
  py::list out;
  for (int k = 0; k < int(scene.walls.size()); ++k) {
    const Vec3 p = sim.wall_point(k), v = sim.wall_velocity(k), n = scene.walls[size_t(k)].normal;
    const Vec3 f = reactions[size_t(k)].force;
    py::dict w;
    w["name"] = scene.walls[size_t(k)].name;
    w["apparatus"] = kind && k >= first && k < last ? kind->name : "";
    w["point"] = py::make_tuple(p[0], p[1], p[2]);
    w["normal"] = py::make_tuple(n[0], n[1], n[2]);
    w["velocity"] = py::make_tuple(v[0], v[1], v[2]);
    w["force"] = py::make_tuple(f[0], f[1], f[2]);
    w["contacts"] = reactions[size_t(k)].contacts;
    const WallServo s = sim.servo_setting(k);
    w["servo"] = s.enabled ? py::object(py::dict(py::arg("target_force") = s.target_force,
                                                 py::arg("gain") = s.gain,
                                                 py::arg("max_speed") = s.max_speed,
                                                 py::arg("integral_time") = s.integral_time,
                                                 py::arg("dead_weight_mass") = s.mass))
                           : py::object(py::none());
    out.append(w);
  }
  return out;
}

py::dict csv_columns(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream cs(line);
    for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
    if (names.empty()) {
      names = cells;
      columns.resize(names.size());
      continue;
    }
    for (std::size_t k = 0; k < names.size(); ++k)  // strtod: subnormals (1e-320 J) read, no throw
      columns[k].push_back(k < cells.size() && !cells[k].empty() ? std::strtod(cells[k].c_str(), nullptr)
                                                                   : NAN);
  }
  py::dict d;
  for (std::size_t k = 0; k < names.size(); ++k) d[py::str(names[k])] = vector_array(std::move(columns[k]));
  return d;
}

// The "key = value" lines of a summary (summary.txt): numbers as floats,
// the rest as text.
py::dict summary_dict(const std::string& text) {
  py::dict d;
  for (const auto& [key, value] : summary_keys(text)) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (end != value.c_str() && *end == '\0') d[py::str(key)] = v;
    else d[py::str(key)] = value;
  }
  return d;
}

struct TestOutcome {
  std::string apparatus, rows_csv, summary, stage, stopped_after;
  bool finished = false;
  long long steps = 0;
};

// The scene's test, as `simsols run SCENE --out DIR` runs it: the one path
// from a scene to its result (apparatus_run.h), the same outputs in `out`.
TestOutcome scene_test(const Scene& scene, const std::string& out, bool quiet,
                       const std::string& stop_at, const std::shared_ptr<Device>& device) {
  ProgrammeRunOptions opt;
  opt.device = device;
  opt.out_dir = out;
  opt.quiet = quiet;
  opt.stop_at = stop_at;
  const TestRun run = simsols::run_scene_test(scene, opt, [&](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "[prepare] %s\n", line.c_str());
  });
  return {run.kind->name,          run.programme->rows_csv(),
          run.programme->summary_text(run.state.wall_seconds),
          run.programme->stage_name(),  run.state.stopped_after,
          run.state.finished,      run.state.steps};
}

py::dict run_test(const Scene& scene, const std::string& out, bool quiet, std::shared_ptr<Device> device,
                  const std::string& stop_at) {
  TestOutcome o;
  {
    py::gil_scoped_release release;
    o = scene_test(scene, out, quiet, stop_at, device_or_open(std::move(device)));
  }
  py::dict r;
  r["apparatus"] = o.apparatus;
  r["finished"] = o.finished;
  r["stage"] = o.stage;
  r["stopped_after"] = o.stopped_after;
  r["checkpoint"] = out + "/checkpoint.bin";
  r["steps"] = o.steps;
  r["summary"] = o.finished ? summary_dict(o.summary) : py::dict();
  r["rows"] = csv_columns(o.rows_csv);
  return r;
}

// The sensitivity study (app/experiment/shear_box/sensitivity.h), as `simsols study
// sensitivity --out OUT --preset PRESET` runs it (resumable the same way):
// its tests, the effects, and the seeds' noise.
py::dict factor_effects(const SensitivityAnalysis& a, int i) {
  py::dict by_response;
  for (int r = 0; r < kSensitivityResponses; ++r) {
    const FactorEffect& e = a.effects[i][r];
    by_response[sensitivity_responses()[r].key] =
        py::dict(py::arg("oat_low") = e.oat_low, py::arg("oat_high") = e.oat_high,
                 py::arg("mu") = e.mu, py::arg("mu_star") = e.mu_star, py::arg("sigma") = e.sigma,
                 py::arg("effects") = e.effects);
  }
  return by_response;
}

py::dict per_response(const std::array<double, kSensitivityResponses>& v) {
  py::dict d;
  for (int r = 0; r < kSensitivityResponses; ++r) d[sensitivity_responses()[r].key] = v[r];
  return d;
}

// A calibration (app/experiment/calibration/calibration.h) as `simsols
// calibrate FILE --out OUT` runs it, resumable the same way: the
// parameters' calibrated values with their posterior, and each curve's fit.
py::dict calibrate(const std::string& path, const std::string& out, bool quiet,
                   std::shared_ptr<Device> device) {
  const CalibrationSpec spec = read_calibration(path);
  CalibrationResult r;
  {
    py::gil_scoped_release release;
    std::filesystem::create_directories(out);
    r = run_calibration(spec, {device_or_open(std::move(device)), out, quiet, {}});
    write_calibration_report(spec, r, out);
  }
  py::dict parameters;
  for (size_t j = 0; j < spec.parameters.size(); ++j) {
    const Estimate& e = r.posterior.estimates[j];
    parameters[spec.parameters[j].name.c_str()] =
        py::dict(py::arg("key") = spec.parameters[j].key, py::arg("calibrated") = r.calibrated[j],
                 py::arg("mean") = e.mean, py::arg("sd") = e.sd, py::arg("lo95") = e.lo95,
                 py::arg("hi95") = e.hi95);
  }
  py::list curves;
  for (const CurveFit& c : r.curves)
    curves.append(py::dict(py::arg("target") = c.target, py::arg("quantity") = c.quantity,
                           py::arg("unit") = c.unit, py::arg("rms_misfit") = c.rms_misfit,
                           py::arg("seed_scatter") = c.seed_scatter));
  return py::dict(py::arg("parameters") = parameters, py::arg("curves") = curves,
                  py::arg("simulations") = r.simulations,
                  py::arg("effective_samples") = r.posterior.effective_samples);
}

// A prediction (prediction.h) as `simsols predict FILE --out OUT`: per
// test and quantity, the band and each specimen's peak.
py::dict predict(const std::string& path, const std::string& out, bool quiet,
                 std::shared_ptr<Device> device) {
  const PredictionSpec spec = read_prediction(path);
  PredictionResult r;
  {
    py::gil_scoped_release release;
    std::filesystem::create_directories(out);
    r = run_prediction(spec, {device_or_open(std::move(device)), out, quiet, {}});
    write_prediction_report(spec, r, out);
  }
  py::dict tests;
  for (const PredictedCurve& c : r.curves) {
    if (!tests.contains(c.test.c_str())) tests[c.test.c_str()] = py::dict();
    tests[c.test.c_str()][c.quantity.c_str()] =
        py::dict(py::arg("x") = c.x, py::arg("mean") = c.mean, py::arg("sd") = c.sd,
                 py::arg("measured") = c.measured, py::arg("peak") = c.peak,
                 py::arg("x_at_peak") = c.x_at_peak, py::arg("rms_error") = c.rms_error,
                 py::arg("inside") = c.inside);
  }
  return tests;
}

py::dict study_sensitivity(const std::string& out, const std::string& preset_name, bool quiet,
                           std::shared_ptr<Device> device) {
  const SensitivityPreset preset = sensitivity_preset(preset_name);
  std::vector<SensitivityTest> tests = plan_sensitivity(preset, out);
  {
    py::gil_scoped_release release;
    CampaignRun run;
    run.device = device_or_open(std::move(device));
    run.quiet = quiet;
    run_sensitivity(tests, preset, out, run);
  }
  std::vector<SensitivityPoint> points;
  std::vector<std::array<double, kSensitivityResponses>> ys;
  py::list rows;
  for (const SensitivityTest& t : tests) {
    points.push_back(t.point);
    ys.push_back(responses_of(t.result.summary));
    py::dict levels;
    for (int i = 0; i < kSensitivityFactors; ++i)
      levels[sensitivity_factors()[i].key.c_str()] = sensitivity_factors()[i].value(t.point.levels[i]);
    py::dict row = per_response(ys.back());
    row["test"] = t.point.label;
    row["design"] = design_name(t.point.design);
    row["seed"] = t.point.seed;
    row["factors"] = levels;
    row["void_ratio"] = t.void_ratio;
    row["shear_void_ratio"] = t.shear_void_ratio;
    row["particles"] = t.scene.particles.size();
    rows.append(row);
  }
  const SensitivityAnalysis a = analyse_sensitivity(points, ys, preset.grid_levels);
  py::dict effects;
  for (int i = 0; i < kSensitivityFactors; ++i)
    effects[sensitivity_factors()[i].key.c_str()] = factor_effects(a, i);
  py::dict r;
  r["tests"] = rows;
  r["effects"] = effects;
  r["base"] = per_response(a.base);
  r["noise_sd"] = per_response(a.noise_sd);
  r["noise_mu_star"] = per_response(a.noise_mu_star);
  r["noise_mean"] = per_response(a.noise_mean);
  r["noise_band"] = per_response(a.noise_band);
  std::array<double, kSensitivityResponses> limit{};
  for (int k = 0; k < kSensitivityResponses; ++k) limit[k] = a.chaos_mu_star_limit(k, preset.trajectories);
  r["chaos_mu_star_limit"] = per_response(limit);
  r["trajectories"] = preset.trajectories;
  return r;
}

// -------------------------------------------------------------- exceptions

void register_exceptions(py::module_& m) {
  // Static (the translator is a plain function) and never destroyed: they
  // must outlive the interpreter's own shutdown.
  static auto* scene_error = new py::exception<SceneError>(m, "SceneError", PyExc_ValueError);
  static auto* runaway_error = new py::exception<RunawayError>(m, "RunawayError", PyExc_RuntimeError);
  static auto* device_error = new py::exception<DeviceError>(m, "DeviceError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      // SceneError and the other input errors: the message names the file,
      // the field and the allowed range; the parts are attributes too
      py::list problems;
      for (const SceneProblem& q : e.problems)
        problems.append(py::dict(py::arg("code") = q.code, py::arg("line") = q.line,
                                 py::arg("field") = q.field, py::arg("message") = q.message));
      py::object instance = py::handle(scene_error->ptr())(e.what());
      instance.attr("file") = e.file;
      instance.attr("line") = e.line;
      instance.attr("field") = e.field;
      instance.attr("code") = e.code;
      instance.attr("problems") = problems;
      PyErr_SetObject(scene_error->ptr(), instance.ptr());
    } catch (const RunawayError& e) {
      (*runaway_error)(e.what());
    } catch (const DeviceError& e) {
      (*device_error)(e.what());
    }
  });
}

void define_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A scene: particles, walls, materials, settings (docs/scene-format.md)")
      .def_property_readonly("particles", [](const Scene& s) { return s.particles.size(); },
                             "How many spheres it holds (those placed so far)")
      .def_property_readonly("placed", &Scene::placed,
                             "False for a scene read but not placed (read_scene): its generators' "
                             "spheres and its apparatus' walls and specimen are still to place")
      .def("place", [](Scene& s) { place_scene(s); },
           "Places what a read scene describes (a run does it first); SceneError names the problem")
      .def("to_toml", [](const Scene& s) { return to_toml(s); }, "The placed scene as TOML text (what the loader reads)")
      .def("to_dict", &scene_to_dict, "The placed scene as nested dicts and lists (to_toml read back)");
  m.def("read_scene", &read_scene, py::arg("path"),
        "Reads and checks a scene file without placing it (fast); SceneError names the problem");
  m.def("load_scene", &load_scene, py::arg("path"), "Reads, checks and places a scene file; SceneError names the problem");
  m.def("parse_scene", &parse_scene, py::arg("text"), py::arg("name") = "<string>",
        "A scene from TOML text; `name` stands for the file in messages");
  m.def("scene_from_dict", &scene_from_dict, py::arg("scene"), py::arg("name") = "<dict>",
        "A scene from nested dicts as a scene file holds them, checked as a file is");
}

void define_simulation(py::module_& m) {
  py::class_<Device, std::shared_ptr<Device>>(m, "Device", "An OpenCL device (SIMSOLS_CL_DEVICE picks it)")
      .def(py::init([] { return Device::open(engine_options_from_environment()); }))
      .def_property_readonly("description", &Device::description)
      .def_property_readonly("is_gpu", &Device::is_gpu);
  py::class_<Simulation>(m, "Simulation", "A scene's model and state on one device")
      .def(py::init([](const Scene& scene, std::shared_ptr<Device> device) {
             if (scene.placed()) return std::make_unique<Simulation>(device_or_open(std::move(device)), scene);
             Scene placed = scene;  // a read scene placed as a run places it
             place_scene(placed);
             return std::make_unique<Simulation>(device_or_open(std::move(device)), placed);
           }),
           py::arg("scene"), py::arg("device") = nullptr)
      .def("advance", &Simulation::advance, py::arg("steps") = 1, py::call_guard<py::gil_scoped_release>(),
           "Steps; RunawayError leaves the state at the step before the fault")
      .def_property_readonly("time", &Simulation::time, "s")
      .def_property_readonly("steps", &Simulation::steps)
      .def_property_readonly("dt", &Simulation::dt, "s")
      .def_property_readonly("particles", [](const Simulation& s) { return s.model().particles(); })
      .def_property_readonly("scene", &Simulation::scene, py::return_value_policy::copy)
      .def("positions", [](Simulation& s) { return vec3_array(s.snapshot().position); }, "(n, 3) m")
      .def("velocities", [](Simulation& s) { return vec3_array(s.snapshot().velocity); }, "(n, 3) m/s")
      .def("angular_velocities", [](Simulation& s) { return vec3_array(s.snapshot().angular_velocity); },
           "(n, 3) rad/s")
      .def("forces", [](Simulation& s) { return vec3_array(s.snapshot().force); }, "(n, 3) N")
      .def("radii", [](Simulation& s) { return vector_array(s.snapshot().radius); }, "(n,) m")
      .def("contact_counts", [](Simulation& s) { return vector_array(s.snapshot().contacts); },
           "(n,) touching neighbours and walls")
      .def("contacts", &contacts_arrays,
           "(pairs (m, 2) int32, forces (m, 3) N): b = -1 - wall for a wall; the force b exerts on a")
      .def("walls", &walls_list,
           "The walls now, as dicts: name, apparatus (its kind, '' for the scene's own), point "
           "(m), normal, velocity (m/s), force the beads exert (N), contacts, servo (None, or "
           "its settings now: target_force N, gain m/(s N), max_speed m/s, integral_time s, "
           "dead_weight_mass kg, 0 for a servo)")
      .def("save_checkpoint", [](Simulation& s, const std::string& path) { save_checkpoint(s, path); },
           py::arg("path"));
  m.def("run_test", &run_test, py::arg("scene"), py::arg("out"), py::arg("quiet") = true,
        py::arg("device") = nullptr, py::arg("stop_at") = "",
        "The scene's test (any apparatus) as `simsols run SCENE --out OUT [--stop-at STAGE]`: "
        "its outputs in `out`; returns apparatus, finished, stage (where it is now), "
        "stopped_after (the stage stop_at ended), checkpoint (its path: load_checkpoint "
        "continues from it), steps, summary (summary.txt's keys) and rows (the rows CSV's "
        "columns as arrays)");
  m.def("study_sensitivity", &study_sensitivity, py::arg("out"), py::arg("preset") = "paper",
        py::arg("quiet") = true, py::arg("device") = nullptr,
        "The sensitivity study as `simsols study sensitivity --out OUT --preset PRESET` (its "
        "files in `out`, resumable): returns tests (one dict each), effects[factor][response] "
        "(oat_low, oat_high, mu, mu_star, sigma, effects), base, noise_mean, noise_sd, noise_band, "
        "noise_mu_star, chaos_mu_star_limit");
  m.def("calibrate", &calibrate, py::arg("path"), py::arg("out"), py::arg("quiet") = true,
        py::arg("device") = nullptr,
        "A calibration as `simsols calibrate PATH --out OUT` (its files in `out`, resumable): "
        "returns parameters[name] (key, calibrated, mean, sd, lo95, hi95), curves (target, "
        "quantity, unit, rms_misfit, seed_scatter), simulations, effective_samples");
  m.def("predict", &predict, py::arg("path"), py::arg("out"), py::arg("quiet") = true,
        py::arg("device") = nullptr,
        "A prediction as `simsols predict PATH --out OUT`: returns [test][quantity] = "
        "dict(x, mean, sd, measured (SI; NaN without a measurement), peak, x_at_peak (per "
        "specimen), rms_error, inside (share of measured points within 2 sd))");
  m.def("load_checkpoint",
        [](const std::string& path, std::shared_ptr<Device> device) {
          return load_checkpoint(device_or_open(std::move(device)), path);
        },
        py::arg("path"), py::arg("device") = nullptr, "A simulation from a checkpoint file");
}

}  // namespace
}  // namespace simsols::python

PYBIND11_MODULE(simsols, m) {
  m.doc() = "SimSols: DEM on OpenCL for geotechnical laboratory tests (docs/python.md)";
  simsols::python::register_exceptions(m);
  simsols::python::define_scene(m);
  simsols::python::define_simulation(m);
}
