// The run request (analysis/run_request.hpp) bound field for field as
// mechkin.RunRequest: Model.run builds one, so Python validates through
// RunRequest::IsValid exactly as the CLI does (the same ranges and messages).
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "analysis/enum_names.hpp"
#include "analysis/run_request.hpp"

namespace mechkin_python {

namespace py = pybind11;

/// ValueError with RunRequest::IsValid's message.
inline void ValidateRequest(const mechkin::RunRequest& r) {
  std::string why;
  if (!r.IsValid(&why)) throw py::value_error(why);
}

// An enum from its name, or ValueError naming the choices.
template <typename E>
E NamedOrThrow(const std::string& field, const std::string& name) {
  E value{};
  if (!mechkin::Parse(name, &value))
    throw py::value_error(field + " must be one of " + mechkin::NameList<E>() + ", not '" + name + "'");
  return value;
}

inline py::object ForcesToPython(mechkin::ForcesChoice f) {
  if (f == mechkin::ForcesChoice::Auto) return py::none();
  return py::bool_(f == mechkin::ForcesChoice::On);
}

inline mechkin::ForcesChoice ForcesFromPython(const std::optional<bool>& f) {
  return !f ? mechkin::ForcesChoice::Auto : *f ? mechkin::ForcesChoice::On : mechkin::ForcesChoice::Off;
}

inline mechkin::RunRequest MakeRequest(int order, double tol, const std::string& solver,
                                       const std::string& formulation,
                                       std::optional<std::vector<std::string>> bodies,
                                       std::optional<std::vector<std::string>> outputs, bool si,
                                       std::optional<bool> forces, std::vector<std::string> sensitivity,
                                       int max_iterations, const std::string& on_limit,
                                       const std::string& on_contact, const std::string& error_bounds) {
  mechkin::RunRequest r;
  r.order = order;
  r.tolerance = tol;
  r.solver = NamedOrThrow<mechkin::PositionSolver>("solver", solver);
  r.formulation = NamedOrThrow<mechkin::Formulation>("formulation", formulation);
  r.bodies = std::move(bodies);
  r.outputs = std::move(outputs);
  r.si = si;
  r.forces = ForcesFromPython(forces);
  r.sensitivity = std::move(sensitivity);
  r.max_iterations = max_iterations;
  r.set_limit_action(NamedOrThrow<mechkin::LimitAction>("on_limit", on_limit));
  r.set_contact_action(NamedOrThrow<mechkin::ContactAction>("on_contact", on_contact));
  r.error_bounds = NamedOrThrow<mechkin::ErrorBoundsChoice>("error_bounds", error_bounds);
  return r;
}

inline std::string RequestRepr(const mechkin::RunRequest& r) {
  auto names = [](const std::optional<std::vector<std::string>>& v) {
    if (!v) return std::string("None");
    std::string s = "[";
    for (size_t k = 0; k < v->size(); ++k) s += (k ? ", '" : "'") + (*v)[k] + "'";
    return s + "]";
  };
  char tol[32];
  std::snprintf(tol, sizeof tol, "%g", r.tolerance);
  const char* forces = r.forces == mechkin::ForcesChoice::Auto ? "None" : r.forces == mechkin::ForcesChoice::On ? "True" : "False";
  return "RunRequest(order=" + std::to_string(r.order) + ", tol=" + tol + ", solver='" + mechkin::ToString(r.solver) +
         "', formulation='" + mechkin::ToString(r.formulation) + "', bodies=" + names(r.bodies) +
         ", outputs=" + names(r.outputs) + ", si=" + (r.si ? "True" : "False") + ", forces=" + forces +
         ", sensitivity=" + names(std::optional<std::vector<std::string>>(r.sensitivity)) + ", on_limit='" +
         mechkin::ToString(r.limit_action()) + "', on_contact='" + mechkin::ToString(r.contact_action()) + "', error_bounds='" +
         mechkin::ToString(r.error_bounds) + "')";
}

inline void BindRunRequest(py::module_& mod) {
  using mechkin::RunRequest;
  py::class_<RunRequest>(mod, "RunRequest", R"doc(What a run computes and shows (the CLI's `run` options), validated
once in the library: RunRequest.is_valid() and Model.run() accept and refuse exactly
the values `mechkin run` does, with the same message.

Fields (defaults): order=3 (0 position ... 4 snap; forces are solved with
accelerations whatever the order shown), tol=1e-10 (position tolerance relative to
the mechanism size, 1e-15 ... 1e-3), solver='newton' ('ceres'),
formulation='omega' ('p'), bodies=None / outputs=None (None: every one; a list
selects), si=False (SI units instead of the file's), forces=None (None: when the
file has inertia or loads), sensitivity=[] (parameter names), max_iterations=25,
on_limit='stop' ('report': a joint reaching its limits is noted and the run goes on;
the CLI's --on-limit), on_contact='report' ('stop': the run ends at the first contact of
a clearance output's bodies; the CLI's --on-contact), error_bounds='auto' (measured near
singular positions and on a sample of the other rows; 'measured': every row, 1.1-3.7x
the time; the CLI's --error-bounds).)doc")
      .def(py::init(&MakeRequest), py::arg("order") = 3, py::arg("tol") = 1e-10, py::arg("solver") = "newton",
           py::arg("formulation") = "omega", py::arg("bodies") = py::none(), py::arg("outputs") = py::none(),
           py::arg("si") = false, py::arg("forces") = py::none(), py::arg("sensitivity") = std::vector<std::string>{},
           py::arg("max_iterations") = 25, py::arg("on_limit") = "stop",
           py::arg("on_contact") = "report", py::arg("error_bounds") = "auto")
      .def_readwrite("order", &RunRequest::order, "highest time derivative shown: 0 position ... 4 snap")
      .def_readwrite("tol", &RunRequest::tolerance, "position tolerance relative to the mechanism size, 1e-15 ... 1e-3")
      .def_property(
          "solver", [](const RunRequest& r) { return std::string(mechkin::ToString(r.solver)); },
          [](RunRequest& r, const std::string& s) { r.solver = NamedOrThrow<mechkin::PositionSolver>("solver", s); },
          "position solver: 'newton' or 'ceres'")
      .def_property(
          "formulation", [](const RunRequest& r) { return std::string(mechkin::ToString(r.formulation)); },
          [](RunRequest& r, const std::string& s) { r.formulation = NamedOrThrow<mechkin::Formulation>("formulation", s); },
          "rotational unknowns of the derivative solves: 'omega' or 'p'")
      .def_readwrite("bodies", &RunRequest::bodies, "body columns shown (None: every body)")
      .def_readwrite("outputs", &RunRequest::outputs, "output columns shown (None: every output)")
      .def_readwrite("si", &RunRequest::si, "SI units (m, rad, N) instead of the file's")
      .def_property(
          "forces", [](const RunRequest& r) { return ForcesToPython(r.forces); },
          [](RunRequest& r, std::optional<bool> f) { r.forces = ForcesFromPython(f); },
          "driver efforts, joint reactions, energies: None (when the file has inertia or loads), True, False")
      .def_readwrite("sensitivity", &RunRequest::sensitivity, "parameters: adds d(column)/d(parameter) columns")
      .def_readwrite("max_iterations", &RunRequest::max_iterations, "Newton iterations per step")
      .def_property(
          "on_limit", [](const RunRequest& r) { return std::string(mechkin::ToString(r.limit_action())); },
          [](RunRequest& r, const std::string& s) {
            r.set_limit_action(NamedOrThrow<mechkin::LimitAction>("on_limit", s));
          },
          "at a joint's limits: 'stop' (the crossing located, motion.stop.kind 'joint_limit') or 'report' "
          "(noted in motion.notes, the run goes on)")
      .def_property(
          "on_contact", [](const RunRequest& r) { return std::string(mechkin::ToString(r.contact_action())); },
          [](RunRequest& r, const std::string& s) {
            r.set_contact_action(NamedOrThrow<mechkin::ContactAction>("on_contact", s));
          },
          "at a first contact of a clearance output's bodies: 'report' (located, in motion.contacts; the run goes "
          "on) or 'stop' (the run ends there, motion.stop.kind 'contact')")
      .def_property(
          "error_bounds", [](const RunRequest& r) { return std::string(mechkin::ToString(r.error_bounds)); },
          [](RunRequest& r, const std::string& s) {
            r.error_bounds = NamedOrThrow<mechkin::ErrorBoundsChoice>("error_bounds", s);
          },
          "rows whose error bounds are measured: 'auto' (near singular positions and a sample of the others) "
          "or 'measured' (every row, 1.1-3.7x the time)")
      .def(
          "is_valid",
          [](const RunRequest& r) {
            std::string why;
            const bool ok = r.IsValid(&why);
            return py::make_tuple(ok, why);
          },
          "(True, '') or (False, why): the CLI's check and message")
      .def("validate", &ValidateRequest, "Raises ValueError with the CLI's message when a field is out of range")
      .def("__repr__", &RequestRepr);
}

}  // namespace mechkin_python
