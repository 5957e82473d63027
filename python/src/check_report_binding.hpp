// `mechkin check`'s report (analysis/check_report.hpp) bound field for field as
// mechkin.CheckReport, its mobility as mechkin.MobilityReport. Attribute names are
// the keys of `mechkin check --format json` (docs in check_command.hpp), so a
// field reads the same from the CLI's JSON and from Python; to_dict() is that JSON.
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "analysis/check_report.hpp"
#include "analysis/enum_names.hpp"
#include "io/check_report_writer.hpp"

namespace mechkin_python {

namespace py = pybind11;

/// The mobility report with the driver count its `dof_after_drivers` needs.
struct PyMobility {
  mechkin::MobilityReport m;
  int drivers = 0;
};

struct PyCheckReport {
  mechkin::CheckReport r;
};

inline py::object ExpectValueToPython(const mechkin::ExpectValue& v) {
  if (v.kind == mechkin::ExpectValue::Kind::Count) return py::int_(v.count);
  if (v.kind == mechkin::ExpectValue::Kind::Word) return py::str(v.word);
  if (v.kind == mechkin::ExpectValue::Kind::Number) return py::float_(v.number);
  return py::none();
}

inline void BindDiagnostic(py::module_& mod) {
  using mechkin::Diagnostic;
  py::class_<Diagnostic>(mod, "Diagnostic", "One problem of a file: pointer (JSON pointer, '' = the whole file), message, fix")
      .def(py::init([](std::string p, std::string m, std::string f) { return Diagnostic{p, m, f}; }),
           py::arg("pointer"), py::arg("message"), py::arg("fix") = "")
      .def_readonly("pointer", &Diagnostic::pointer, "JSON pointer of the offending value ('' = whole file)")
      .def_readonly("message", &Diagnostic::message, "what is wrong")
      .def_readonly("fix", &Diagnostic::fix, "how to fix it")
      .def("__iter__", [](const Diagnostic& d) { return py::iter(py::make_tuple(d.pointer, d.message, d.fix)); })
      .def("__eq__", [](const Diagnostic& a, const Diagnostic& b) {
        return a.pointer == b.pointer && a.message == b.message && a.fix == b.fix;
      })
      .def("__str__", [](const Diagnostic& d) {
        return (d.pointer.empty() ? std::string("(file)") : d.pointer) + ": " + d.message +
               (d.fix.empty() ? "" : " (fix: " + d.fix + ")");
      })
      .def("__repr__", [](const Diagnostic& d) {
        return "Diagnostic(" + py::repr(py::str(d.pointer)).cast<std::string>() + ", " +
               py::repr(py::str(d.message)).cast<std::string>() + ")";
      });
}

inline void BindMobility(py::module_& mod) {
  using mechkin::MobilityReport;
  py::class_<PyMobility>(mod, "MobilityReport",
                         "Rank-based mobility at the design pose (`mechkin check`'s \"mobility\" object; "
                         "the same keys as its JSON)")
      .def_property_readonly("assembled", [](const PyMobility& p) { return p.m.assembled; }, "the design pose assembled")
      .def_property_readonly("assembly", [](const PyMobility& p) { return p.m.assembly_message; }, "why not, when not")
      .def_property_readonly("equations", [](const PyMobility& p) { return p.m.equations; }, "joint equations")
      .def_property_readonly("rank", [](const PyMobility& p) { return p.m.rank; }, "rank of the joints' Jacobian")
      .def_property_readonly("mobility", [](const PyMobility& p) { return p.m.mobility; }, "freedoms of the joints (6n - rank)")
      .def_property_readonly("redundant", [](const PyMobility& p) { return p.m.redundant; }, "redundant equations (m - rank)")
      .def_property_readonly("rank_method", [](const PyMobility& p) { return p.m.rank_method; }, "'svd' or 'sparse-qr'")
      .def_property_readonly("sigma_min_kept", [](const PyMobility& p) { return p.m.sigma_min_kept; }, "rank margin: smallest kept")
      .def_property_readonly("sigma_max_dropped", [](const PyMobility& p) { return p.m.sigma_max_dropped; }, "rank margin: largest dropped")
      .def_property_readonly("redundant_equations", [](const PyMobility& p) {
        py::list out;
        for (const auto& e : p.m.redundant_equations) out.append(py::dict(py::arg("equation") = e.description, py::arg("fixed_by") = e.fixed_by));
        return out;
      }, "[{equation, fixed_by}]: the equations set aside and the joints that already fix them")
      .def_property_readonly("idle", [](const PyMobility& p) {
        py::list out;
        for (const auto& f : p.m.idle)
          out.append(py::dict(py::arg("bodies") = f.body, py::arg("axis") = std::vector<double>{f.axis.x(), f.axis.y(), f.axis.z()},
                              py::arg("description") = f.description));
        return out;
      }, "[{bodies, axis, description}]: idle freedoms (a spin that moves nothing else)")
      .def_property_readonly("dof_after_drivers", [](const PyMobility& p) { return p.m.mobility - p.drivers; },
                             "mobility - drivers (negative: over-driven)")
      .def_property_readonly("free_after_drivers", [](const PyMobility& p) { return p.m.dof_after_drivers; },
                             "freedoms the joints and drivers together leave (never negative)")
      .def_property_readonly("driven", [](const PyMobility& p) { return std::string(mechkin::ToString(p.m.driving_status)); },
                             "'full', 'under' or 'over'")
      .def_property_readonly("conflicting_drivers", [](const PyMobility& p) { return p.m.conflicting_drivers; },
                             "drivers that fight each other or the joints")
      .def_property_readonly("remaining_freedoms", [](const PyMobility& p) { return p.m.remaining_freedoms; },
                             "the freedoms no driver controls, in words")
      .def_property_readonly("verdict", [](const PyMobility& p) { return p.m.verdict; }, "the verdict in words ('' when regular)")
      .def_property_readonly("suggestions", [](const PyMobility& p) { return p.m.suggestions; }, "how to fix the verdict")
      .def_property_readonly("locked", [](const PyMobility& p) { return p.m.locked; }, "the joints alone lock the mechanism")
      .def_property_readonly("locking_joints", [](const PyMobility& p) { return p.m.locking_joints; },
                             "joints whose removal alone frees a locked mechanism")
      .def_property_readonly("singular_design_pose", [](const PyMobility& p) { return p.m.singular_lost > 0; },
                             "the design pose is a singular position of the driven mechanism")
      .def_property_readonly("singular_directions", [](const PyMobility& p) { return p.m.singular_directions; },
                             "the directions the drivers lose there")
      .def("__getitem__", [](py::object self, const std::string& key) { return self.attr(key.c_str()); },
           "report.mobility['redundant'] reads like report.mobility.redundant")
      .def("get", [](py::object self, const std::string& key, py::object dflt) {
        return py::hasattr(self, key.c_str()) ? self.attr(key.c_str()) : dflt;
      }, py::arg("key"), py::arg("default") = py::none(), "report.mobility.get('driven'): a field, or default")
      .def("__repr__", [](const PyMobility& p) {
        return "MobilityReport(mobility=" + std::to_string(p.m.mobility) + ", redundant=" + std::to_string(p.m.redundant) +
               ", driven='" + mechkin::ToString(p.m.driving_status) + "')";
      });
}

void BindCheckReportFields(py::class_<PyCheckReport>& c);

inline void BindCheckReport(py::module_& mod) {
  BindDiagnostic(mod);
  BindMobility(mod);
  py::class_<PyCheckReport> c(mod, "CheckReport",
                              "`mechkin check`'s report of one file: validity, counts, the Grübler count, the "
                              "rank-based mobility, the file's expectations; the fields are the keys of "
                              "`mechkin check --format json`");
  BindCheckReportFields(c);
}

inline void BindCheckReportFields(py::class_<PyCheckReport>& c) {
  c.def_property_readonly("file", [](const PyCheckReport& p) { return p.r.file; }, "the file checked")
      .def_property_readonly("valid", [](const PyCheckReport& p) { return p.r.valid; }, "the file compiles")
      .def_property_readonly("ok", [](const PyCheckReport& p) { return p.r.ok(); }, "valid and every expectation held")
      .def_property_readonly("name", [](const PyCheckReport& p) { return p.r.name; }, "the file's name")
      .def_property_readonly("errors", [](const PyCheckReport& p) { return p.r.errors; }, "[Diagnostic]")
      .def_property_readonly("warnings", [](const PyCheckReport& p) { return p.r.warnings; }, "[Diagnostic]")
      .def_property_readonly("bodies", [](const PyCheckReport& p) { return p.r.bodies; }, "moving bodies")
      .def_property_readonly("drivers", [](const PyCheckReport& p) { return p.r.drivers; }, "number of drivers")
      .def_property_readonly("joints", [](const PyCheckReport& p) {
        py::dict d;
        for (const auto& kv : p.r.joints) d[py::str(kv.first)] = kv.second;
        return d;
      }, "{type: count}, in first-seen order")
      .def_property_readonly("grubler", [](const PyCheckReport& p) { return p.r.grubler; }, "Grübler-Kutzbach count")
      .def_property_readonly("dof_after_drivers_count", [](const PyCheckReport& p) { return p.r.dof_after_drivers_count; },
                             "Grübler count - drivers")
      .def_property_readonly("mobility", [](const PyCheckReport& p) -> py::object {
        if (!p.r.mobility) return py::none();
        return py::cast(PyMobility{*p.r.mobility, p.r.drivers});
      }, "MobilityReport, or None when the file is invalid")
      .def_property_readonly("expect", [](const PyCheckReport& p) {
        py::list out;
        for (const auto& e : p.r.expectations)
          out.append(py::dict(py::arg("key") = e.key, py::arg("expected") = ExpectValueToPython(e.expected),
                              py::arg("actual") = ExpectValueToPython(e.actual), py::arg("held") = e.held));
        return out;
      }, "[{key, expected, actual, held}]: the file's `expect` block")
      .def_property_readonly("branches", [](const PyCheckReport& p) -> py::object {
        if (!p.r.branches) return py::none();
        return py::dict(py::arg("count") = p.r.branches->branches, py::arg("restarts") = p.r.branches->restarts,
                        py::arg("converged") = p.r.branches->converged,
                        py::arg("distances_from_design") = p.r.branches->distances);
      }, "with check(branches=...): the assembly branches found")
      .def("to_dict", [](const PyCheckReport& p) {
        return py::module_::import("json").attr("loads")(mechkin::CheckReportJsonText(p.r));
      }, "The `mechkin check --format json` object of this file")
      .def("__repr__", [](const PyCheckReport& p) {
        std::string s = "CheckReport(" + py::repr(py::str(p.r.name)).cast<std::string>() + ", valid=" + (p.r.valid ? "True" : "False");
        if (p.r.mobility)
          s += ", mobility=" + std::to_string(p.r.mobility->mobility) + ", driven='" + mechkin::ToString(p.r.mobility->driving_status) + "'";
        return s + ", ok=" + (p.r.ok() ? "True" : "False") + ")";
      });
}

}  // namespace mechkin_python
