"""mechkin: spatial kinematics of mechanisms, over the same C++ core as the CLI.

    import mechkin
    model = mechkin.load("mechanisms/spatial-slider-crank.json")
    motion = model.run()                 # a Motion; numpy views of the core's table
    motion.t, motion["piston.x_tt"], motion.body("rod").position(1)
    motion.to_pandas()                   # needs pandas
    model.check().mobility.redundant     # the `mechkin check` report, field for field
    mechkin.sweep(model, [{"rod": 110}, {"rod": 130}])  # a pandas DataFrame, one row per variant
    mechkin.sweep(model, variants, out="data", curves=["coupler_point.x"])  # every row, into data/sweep.h5
    mechkin.Mechanism("four-bar").add_body(...)  # a builder: to_dict(), compile() (mechkin/builder.py)

Every front end validates through the same run request (mechkin.RunRequest):
model.run(tol=5e-3) is refused with the message `mechkin run --tol 5e-3` prints.

Models are immutable and pickle (as their file text); a Motion pickles too.
Runs release the GIL, so a model can be run from several threads at once.
"""
import json as _json

import numpy as _np
from numpy.lib.stride_tricks import as_strided as _as_strided

from . import _mechkin
from .builder import Mechanism

__all__ = ["load", "loads", "Mechanism", "Model", "Motion", "RunRequest", "CheckReport", "MobilityReport", "RangeReport",
           "ToleranceReport", "OptimizeResult", "FormatError", "Diagnostic", "RunStop", "Contact", "sweep"]

RunRequest = _mechkin.RunRequest
CheckReport = _mechkin.CheckReport
MobilityReport = _mechkin.MobilityReport
Diagnostic = _mechkin.Diagnostic


class FormatError(ValueError):
    """An invalid mechanism file. `diagnostics` lists every problem, not only the first."""

    def __init__(self, source, diagnostics):
        self.source = source
        self.diagnostics = [d if isinstance(d, Diagnostic) else Diagnostic(*d) for d in diagnostics]
        lines = ["%s: %d error(s)" % (source, len(self.diagnostics))] + ["  " + str(d) for d in self.diagnostics]
        super().__init__("\n".join(lines))


def _compile(text, source, overrides=None):
    core, errors, warnings = _mechkin.compile(text, source, dict(overrides or {}))
    if core is None:
        raise FormatError(source, errors)
    return Model(core)


def load(path, drive=None, span=None):
    """Reads and compiles a mechanism file (format v1), or imports a URDF, MJCF,
    SDFormat or FreeCAD file (docs/import.md; detected by extension and content).

    A foreign file has no drivers: drive={"crank": "2*pi*t"} drives joints by
    functions of t (rad or m), over span=(start, end, steps) (default 0, 1, 360).
    Raises FormatError: for a foreign file, each diagnostic's pointer is the place
    in that file (FILE:LINE: <element>)."""
    path = str(path)
    if _mechkin.foreign_format(path):
        return _load_foreign(path, drive, span)
    if drive is not None or span is not None:
        raise ValueError("%s: drive= and span= are for imported (URDF, MJCF, SDFormat, FreeCAD) files; "
                         "a mechanism file has its own drivers and analysis" % path)
    with open(path, "rb") as f:
        data = f.read()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise FormatError(path, [("", "the file is not UTF-8 text (byte %d)" % e.start,
                                  "save the file as UTF-8")]) from None
    return _compile(text, path)


def _load_foreign(path, drive, span):
    drives = [(str(k), str(v)) for k, v in dict(drive or {}).items()]
    if span is not None:
        start, end, steps = span
        if not (float(end) > float(start)) or int(steps) != steps or not 1 <= int(steps) <= 10 ** 7:
            raise ValueError("span=%r: expected (start, end, steps) with end > start and 1 <= steps <= 1e7, "
                             "e.g. span=(0, 1, 360)" % (span,))
        span = [float(start), float(end), float(steps)]
    core, errors, warnings = _mechkin.compile_file(path, {}, drives, span or [])
    if core is None:
        raise FormatError(path, errors)
    return Model(core)


def loads(text_or_dict, source="<string>"):
    """Compiles a mechanism from JSON text or from a dict. Raises FormatError."""
    if isinstance(text_or_dict, dict):
        text_or_dict = _json.dumps(text_or_dict)
    return _compile(text_or_dict, source)


class _Report:
    """A report of the core as attributes (its JSON form's keys), with the CLI's text
    as str(report). ok is False with .message saying why when it could not be made."""

    def __init__(self, json_text, text):
        self._data, self._text = _json.loads(json_text), text

    def __getattr__(self, key):
        try:
            return self._data[key]
        except KeyError:
            raise AttributeError(key) from None

    ok = property(lambda self: bool(self._data["ok"]), doc="the report could be made (else .message says why)")

    def to_dict(self):
        """The CLI's `--format json` object."""
        return _json.loads(_json.dumps(self._data))

    def __str__(self):
        return self._text


class RangeReport(_Report):
    """`mechkin range`: per driver its design value and both ends (kind, value, message)."""

    def __getitem__(self, driver):
        """The driver's range: {driver, unit, design_value, lower, upper, ...}."""
        for d in self._data["drivers"]:
            if d["driver"] == driver:
                return d
        raise KeyError(driver)

    def __repr__(self):
        return "RangeReport(%s)" % ", ".join("%s: %s..%s" % (d["driver"], d["lower"]["value"], d["upper"]["value"])
                                              for d in self._data.get("drivers", []))


class ToleranceReport(_Report):
    """`mechkin tolerance`: per output column the worst case and RSS at every row."""

    def column(self, name):
        """One output column's stack-up: {name, unit, worst_case, rss, contributions, ...}."""
        for c in self._data["columns"]:
            if c["name"] == name:
                return c
        raise KeyError(name)

    def to_pandas(self):
        """One row per time: worst case and RSS of every column (`C worst_case`, `C rss`);
        columns with no stack-up (`not_computed`: a velocity ratio at order 0) are left out."""
        import pandas as pd
        frame = {"t": self._data["t"]}
        for c in self._data["columns"]:
            if "not_computed" in c:
                continue
            frame[c["name"] + " worst_case"] = c["worst_case"]
            frame[c["name"] + " rss"] = c["rss"]
        return pd.DataFrame(frame)

    def __repr__(self):
        return "ToleranceReport(%d columns, parameters %s)" % (len(self._data.get("columns", [])),
                                                              sorted(self._data.get("tolerances", {})))


class OptimizeResult(_Report):
    """`mechkin optimize` (Model.optimize): the report's fields as attributes —
    converged, objective_before, objective_after, parameters ([{name, before, after,
    gradient}]), iterations, gradient_norm, best_start, active_bounds, constraints
    ([{reduction, relation, bound, value, active}]), starts (per start: initial, final,
    objective_initial, objective_final, iterations, ok, feasible, failed_evaluations,
    failures, termination) — and .model, the Model with the optimised values (None when
    no start ran). str(result) is the CLI's text report."""

    def __init__(self, json_text, text, model, values):
        super().__init__(json_text, text)
        self.model = model
        self.values = dict(values)

    def __repr__(self):
        return "OptimizeResult(%s: %s -> %s, %s, %s)" % (
            self._data["minimize"], self._data["objective_before"], self._data["objective_after"],
            "converged" if self._data["converged"] else "not converged",
            ", ".join("%s=%.10g" % kv for kv in self.values.items()))


class Model:
    """A compiled, immutable mechanism (load() or loads() make one).

    Fields: name, source (the file), bodies, joints ([{name, type, body1, body2}]),
    drivers, outputs, units ({length, angle}: the file's units, used by every table
    unless run(si=True)), analysis ({start, end, steps} or None), warnings
    ([Diagnostic]), parameters ({name: value}), parameter_info ({name: {value,
    tolerance, min, max, expression}}).

    Methods: run() -> Motion, check() -> CheckReport, range() -> RangeReport,
    tolerance() -> ToleranceReport, with_parameters(**values) -> Model,
    optimize(vary, minimize) -> OptimizeResult, objective(name, values) and
    gradient(name, values) for one's own optimiser.
    Models pickle (as their file text and parameter values)."""

    def __init__(self, core):
        self._core = core
        self._info = core.info()

    name = property(lambda self: self._info["name"], doc="the file's name")
    source = property(lambda self: self._info["source"], doc="where the model was read from")
    bodies = property(lambda self: list(self._info["bodies"]), doc="moving bodies' names, in file order")
    joints = property(lambda self: [dict(j) for j in self._info["joints"]],
                      doc="[{name, type, body1, body2}] in file order")
    couplers = property(lambda self: [dict(c) for c in self._info["couplers"]],
                        doc="[{name, type, joints}]: the couplers between joint coordinates (gears, racks, ...)")
    drivers = property(lambda self: list(self._info["drivers"]), doc="drivers' names")
    outputs = property(lambda self: list(self._info["outputs"]), doc="outputs' names")
    units = property(lambda self: dict(self._info["units"]), doc="{length, angle}: the file's units")
    analysis = property(lambda self: None if self._info["analysis"] is None else dict(self._info["analysis"]),
                        doc="{start, end, steps} of the file's analysis block, or None")
    warnings = property(lambda self: list(self._info["warnings"]), doc="[Diagnostic]: the file's warnings")
    parameters = property(lambda self: {k: v["value"] for k, v in self._info["parameters"].items()},
                          doc="the file's parameters and their (resolved) values")
    parameter_info = property(lambda self: {k: dict(v) for k, v in self._info["parameters"].items()},
                              doc="per parameter: value, tolerance, min, max, expression")

    def with_parameters(self, **values):
        """The same file compiled with other parameter values (like `mechkin run --set`).
        Raises FormatError when a value makes the geometry invalid."""
        core, errors, _ = self._core.with_parameters({k: float(v) for k, v in values.items()})
        if core is None:
            raise FormatError(self._core.source, errors)
        return Model(core)

    def optimize(self, vary, minimize, subject_to=(), starts=1, seed=0, max_iterations=100, order=3, tol=1e-12):
        """Minimise the reduction `minimize` over the parameters `vary`, like `mechkin
        optimize` (Ceres, exact gradients from the sensitivities; bounds: the parameters'
        min/max; subject_to: ["R >= v", "R <= v"] by quadratic penalty; starts: the file's
        values, then starts - 1 drawn with `seed`). Returns an OptimizeResult whose
        .model is the Model with the optimised values."""
        vary = [vary] if isinstance(vary, str) else list(vary)
        subject_to = [subject_to] if isinstance(subject_to, str) else list(subject_to)
        data, text, values = self._core.optimize(vary, minimize, subject_to, int(starts), int(seed),
                                                 int(max_iterations), int(order), float(tol))
        report = _json.loads(data)
        model = self.with_parameters(**values) if report["best_start"] >= 0 else None
        return OptimizeResult(data, text, model, values)

    def _objective(self, name, values, vary, order, tol):
        if isinstance(values, dict):
            vary, values = list(values), [float(v) for v in values.values()]
        else:
            if vary is None:
                raise ValueError("pass vary=[parameter names] with an array of values (or pass a dict)")
            vary = [vary] if isinstance(vary, str) else list(vary)
            values = [float(v) for v in _np.asarray(values, dtype=float).ravel()]
        return self._core.objective(name, vary, values, int(order), float(tol))

    def objective(self, name, values, vary=None, order=3, tol=1e-12):
        """The reduction `name` for the parameter values given ({name: value}, or an array
        in the order of `vary`): one run of the variant. Raises ValueError when the
        variant does not assemble or its run stops (the message says why)."""
        return self._objective(name, values, vary, order, tol)[0]

    def gradient(self, name, values, vary=None, order=3, tol=1e-12):
        """d(reduction)/d(parameter) as a numpy array, in the order of the dict's keys or
        of `vary`: exact, from one run with sensitivities (for scipy.optimize's jac=)."""
        return _np.asarray(self._objective(name, values, vary, order, tol)[1], dtype=float)

    def check(self):
        """The `mechkin check` report (CheckReport): Grübler count, rank mobility,
        redundancy, idle freedoms, driving status, expectations."""
        return self._core.check()

    def range(self, driver=None, steps=360, span=None, tol=1e-10):
        """Range of motion of each driver (or of `driver`) from the design pose, like
        `mechkin range`: each end located and labelled 'limit', 'branch point', 'joint limit',
        'full turn', 'open' or 'failed'. span: search span of translations and
        distances in file units (default 4x the mechanism's size)."""
        data, text = self._core.range(driver or "", int(steps), 0.0 if span is None else float(span), float(tol))
        return RangeReport(data, text)

    def tolerance(self, order=0, monte_carlo=0, seed=1, threads=None, tol=1e-10):
        """Tolerance stack-up of the outputs, like `mechkin tolerance`: per column and
        row the worst case and RSS from exact sensitivities, the parameters ranked by
        contribution, and with monte_carlo=N a seeded Monte-Carlo check."""
        data, text = self._core.tolerance(int(order), int(monte_carlo), int(seed), int(threads or 0), float(tol))
        return ToleranceReport(data, text)

    def run(self, order=3, tol=1e-10, solver="newton", formulation="omega", bodies=None, outputs=None,
            si=False, start=None, end=None, steps=None, forces=None, sensitivity=None, on_limit="stop",
            on_contact="report", error_bounds="auto", request=None):
        """The driven kinematic analysis, like `mechkin run`. Returns a Motion; a run
        that stops early returns the rows computed with motion.complete False and
        motion.stop saying why.

        The arguments are a RunRequest's fields (or pass request=RunRequest(...)):
        order 0..4 shown, tol in [1e-15, 1e-3], solver, formulation, bodies/outputs
        (None: all), si, forces (None: when the file has inertia or loads; solved with
        accelerations whatever the order shown, their rates with order >= 3),
        sensitivity (parameter names: d(column)/d(parameter) columns), on_limit
        ('stop': a joint reaching its limits ends the run there, motion.stop.kind
        'joint_limit' naming the joint; 'report': noted in motion.notes and the run
        goes on; `run --on-limit`), on_contact ('report': a first contact of a
        clearance output's bodies is located and the run goes on; 'stop': the run
        ends there, motion.stop.kind 'contact'; either way motion.contacts lists
        them; `run --on-contact`), error_bounds ('auto': measured near singular
        positions and on a sample of the other rows, which raises the condition
        estimate's bounds where they fall short; 'measured': every row, 1.1-3.7x
        the time; `run --error-bounds`). Out-of-range values raise ValueError with the
        CLI's message. start, end, steps replace the file's analysis span."""
        if request is None:
            norm = lambda sel: None if sel is None else ([sel] if isinstance(sel, str) else list(sel))
            request = RunRequest(order=int(order), tol=float(tol), solver=solver, formulation=formulation,
                                 bodies=norm(bodies), outputs=norm(outputs), si=bool(si), forces=forces,
                                 sensitivity=norm(sensitivity) or [], on_limit=on_limit,
                                 on_contact=on_contact, error_bounds=error_bounds)
        core = self._core.run(request, start, end, steps)
        return Motion(self, core, dict(order=request.order, si=request.si, bodies=request.bodies,
                                       outputs=request.outputs, forces=core.forces,
                                       sensitivity=list(request.sensitivity)))

    def __reduce__(self):
        return (_compile, (self._core.text, self._core.source, dict(self._core.overrides)))

    def __repr__(self):
        return "Model(%r, %d bodies, %d joints, %d drivers)" % (self.name, len(self.bodies), len(self.joints), len(self.drivers))


class RunStop:
    """Why a run ended early. Fields: kind ('refused', 'assembly_failed',
    'singular_position', 'solve_failed', 'interrupted', 'joint_limit', 'contact';
    'none' for a complete run),
    message (the CLI's explanation), singular (dict(t, driver_values, joint_mobility,
    involved) or None), limit (where a position solve failed: dict(t, driver_values
    in SI, fold) or None). False for a complete run."""

    def __init__(self, report):
        self.kind = report["stop"]
        self.message = report["message"]
        self.singular = report["singular"]  # dict(t, driver_values, joint_mobility, involved) or None
        # where a position solve failed: dict(t, driver_values (SI), fold) or None
        self.limit = report.get("limit")

    def __bool__(self):
        return self.kind != "none"

    def __repr__(self):
        return "RunStop(%r, %r)" % (self.kind, self.message.split("\n")[0])


class Contact:
    """A first contact of a clearance output's bodies, located on the exact motion
    (`run --on-contact`): t (s), output (the clearance output's name), body1, body2,
    point (numpy [x, y, z], global, the motion's length unit: between the closest
    points at t), driver_values (SI, at t), at_start (True: already touching on the
    first row, not located; then clearance is the (negative) clearance there)."""

    def __init__(self, d):
        self.t = d["t"]
        self.output = d["output"]
        self.body1, self.body2 = d["body1"], d["body2"]
        self.point = _np.array(d["point"])
        self.driver_values = list(d["driver_values"])
        self.at_start = d["at_start"]
        self.clearance = d["clearance"]

    @property
    def bodies(self):
        """(body1, body2)"""
        return (self.body1, self.body2)

    def __repr__(self):
        return "Contact(t=%.12g, bodies=%r, point=%s)" % (self.t, self.bodies, list(self.point))


class _Series:
    """Typed access to one body's columns, as zero-copy numpy views."""

    def __init__(self, motion, name):
        self._m, self._name = motion, name

    def _xyz(self, quantity, order):
        cols = [self._m._find(quantity, self._name, a, order) for a in range(3)]
        if None in cols:
            raise KeyError("%s has no %s of order %d in this motion" % (self._name, quantity, order))
        return self._m._strided(cols)

    def position(self, order=0):
        """Origin (order 0) or its order-th time derivative, rows × 3 (global)."""
        return self._xyz("body_position", order)

    def angular_velocity(self, order=1):
        """Global angular velocity (order 1) or its derivatives (order 2: acceleration …), rows × 3."""
        return self._xyz("angular_velocity", order)

    def euler_parameters(self):
        """Euler parameters e0..e3 (scalar first), rows × 4."""
        return self._m._strided([self._m._find("euler_parameter", self._name, a, 0) for a in range(4)])


class Motion:
    """The result of a run: a table of rows (time steps) × typed columns.

    Fields: model, values (read-only rows × columns numpy view of the C++ buffer),
    columns ([{name, unit, quantity, subject, component, order}]: what each column
    is), names (the column names, as in the CLI's table without units), t (time, s),
    complete, stop (RunStop), set_aside, reselections, notes, indeterminate_reactions,
    diagnostics. Units: the file's (run(si=True): SI), stated per column by
    units() and not repeated in the names.

    Access: motion[name], body(name).position(order), effort(driver),
    clearance(output), closest_points(output), contacts (first contacts),
    power(driver), reaction(joint), sensitivity(column, parameter) — views into
    values (no copies); to_pandas(), to_csv(path), to_json(path). Motions pickle."""

    def __init__(self, model, core, options):
        self.model = model
        self._core = core
        self._options = options
        self.columns = core.columns()
        self._index = {c["name"]: k for k, c in enumerate(self.columns)}
        self._report = core.report()
        self.values = core.values

    complete = property(lambda self: self._report["complete"], doc="the run reached its last row")
    stop = property(lambda self: RunStop(self._report), doc="RunStop: why the run ended early (falsy when complete)")
    set_aside = property(lambda self: list(self._report["set_aside"]), doc="redundant equations set aside")
    notes = property(lambda self: list(self._report.get("notes", [])),
                     doc="singular positions the run passed uniquely (went on), one line each; as `run` prints")
    reselections = property(lambda self: list(self._report.get("reselections", [])),
                            doc="[(t, equations set aside from t on)]: redundancy that follows the motion")
    names = property(lambda self: [c["name"] for c in self.columns], doc="column names (units in units())")
    contacts = property(lambda self: [Contact(c) for c in self._report.get("contacts", [])],
                        doc="[Contact]: first contacts of clearance outputs' bodies, earliest first")
    reductions = property(lambda self: {r["name"]: r for r in self._report.get("reductions", [])},
                          doc="{name: dict}: the file's reductions (value, unit, t, located, gradient, problem)")
    first_contact = property(lambda self: next(iter(self.contacts), None),
                             doc="the earliest Contact, or None")
    t = property(lambda self: self.values[:, 0], doc="time of each row, s")

    def __len__(self):
        return self.values.shape[0]

    def __getitem__(self, name):
        try:
            return self.values[:, self._index[name]]
        except KeyError:
            raise KeyError("no column %r; motion.names lists them" % name) from None

    def _find(self, quantity, subject, component, order):
        for k, c in enumerate(self.columns):
            if (c["quantity"] == quantity and c["subject"] == subject and c["component"] == component
                    and c["order"] == order):
                return k
        return None

    def _strided(self, cols):
        """Columns at a constant spacing as one rows × len(cols) view."""
        v = self.values
        if len(cols) > 1:
            step = cols[1] - cols[0]
            if any(b - a != step for a, b in zip(cols, cols[1:])):
                raise ValueError("columns are not evenly spaced")
        else:
            step = 1
        base = v[:, cols[0]:]
        return _as_strided(base, shape=(v.shape[0], len(cols)), strides=(v.strides[0], step * v.strides[1]),
                           writeable=False)

    def body(self, name):
        """Typed access to one body's columns: .position(order), .angular_velocity(order), .euler_parameters()."""
        if name not in self.model.bodies:
            raise KeyError("no body %r" % name)
        return _Series(self, name)

    @property
    def diagnostics(self):
        """Per row: newton_iterations, residual, condition, error_bound (rows × (order+1))."""
        order = self._options["order"]
        first_bound = self._index["error_bound"]
        return {
            "newton_iterations": self["newton_iterations"],
            "residual": self["residual"],
            "condition": self["condition"],
            "error_bound": self._strided(list(range(first_bound, first_bound + order + 1))),
        }

    def units(self):
        """{column name: unit} ('' for dimensionless columns)."""
        return {c["name"]: c["unit"] for c in self.columns}

    def sensitivity(self, column, parameter):
        """d(column)/d(parameter) per row (run with sensitivity=[parameter])."""
        base = self._index.get(column)
        for k, c in enumerate(self.columns):
            if c.get("wrt") == parameter and c.get("base") == base and base is not None:
                return self.values[:, k]
        raise KeyError("no sensitivity of %r to %r in this motion (run with sensitivity=[%r])" % (column, parameter, parameter))

    @property
    def indeterminate_reactions(self):
        """With redundant equations: the reaction components statics cannot determine."""
        return list(self._report.get("indeterminate_reactions", []))

    def effort(self, driver, order=0):
        """The torque (rotation) or force (translation, distance) the driver applies; order 1: its rate."""
        return self._rated("driver_effort", driver, order)

    def power(self, driver, order=0):
        """The power the driver delivers; order 1: its rate."""
        return self._rated("driver_power", driver, order)

    def _rated(self, quantity, driver, order):
        k = self._find(quantity, driver, -1, order)
        if k is None:
            raise KeyError("no %s of driver %r at order %d in this motion (run with forces=True)"
                           % (quantity.replace("driver_", ""), driver, order))
        return self.values[:, k]

    def clearance(self, output, order=0):
        """A clearance output's smallest distance between its bodies' shapes per row
        (negative: penetration depth); order 1: its rate. The motion's length unit."""
        k = self._find("clearance", output, -1, order)
        if k is None:
            raise KeyError("no clearance %r of order %d in this motion" % (output, order))
        return self.values[:, k]

    def closest_points(self, output):
        """(point1, point2): the closest points on body1's and body2's shapes, rows × 3 each (global)."""
        cols = [self._find("clearance_point", output, c, 0) for c in range(6)]
        if None in cols:
            raise KeyError("no clearance %r in this motion" % output)
        return self._strided(cols[:3]), self._strided(cols[3:])

    def reaction(self, joint, frame="global", order=0):
        """(force, moment) that body1 exerts on body2 at the joint origin, rows × 3 each:
        frame "global" (x, y, z) or "joint" (body2's joint frame f, g, h; h is the axis)."""
        q = ("joint_force", "joint_moment") if frame == "global" else ("joint_force_local", "joint_moment_local")
        out = []
        for quantity in q:
            cols = [self._find(quantity, joint, a, order) for a in range(3)]
            if None in cols:
                raise KeyError("no %s reaction of %r in this motion (run with forces=True)" % (frame, joint))
            out.append(self._strided(cols))
        return tuple(out)

    def to_pandas(self):
        """A pandas DataFrame with the table's column names (units in df.attrs['units'])."""
        try:
            import pandas
        except ImportError:
            raise ImportError("Motion.to_pandas() needs pandas: install python3-pandas "
                              "(apt-get install python3-pandas) or pip install pandas") from None
        df = pandas.DataFrame(self.values, columns=self.names, copy=False)
        df.attrs["units"] = self.units()
        return df

    def to_csv(self, path):
        """Writes the same CSV as `mechkin run -o path` (atomically); never onto the model's file."""
        self._core.write(str(path), "csv", [self.model._core.source])

    def to_json(self, path):
        """Writes the same JSON as `mechkin run --format json -o path` (atomically); never onto the model's file."""
        self._core.write(str(path), "json", [self.model._core.source])

    def __reduce__(self):
        o = self._options
        return (_rebuild_motion, (self.model, o, _np.array(self.values), self._report))

    def __repr__(self):
        return "Motion(%d rows × %d columns, complete=%s)" % (self.values.shape[0], self.values.shape[1], self.complete)


def _rebuild_motion(model, options, values, report):
    core = _mechkin.motion_from_state(model._core, options["order"], options["si"], options["bodies"],
                                      options["outputs"], options.get("forces", False), values, report["complete"], report["stop"],
                                      report["message"], options.get("sensitivity", []))
    m = Motion(model, core, options)
    m._report = dict(report)
    return m


def _run_variant(model, values, order, tol):
    return model._core.run_variant({k: float(v) for k, v in values.items()}, int(order), float(tol))


class _DeferredInterrupt:
    """Ctrl-C noted instead of raised while the main thread feeds and watches a thread
    pool. Raised anywhere, KeyboardInterrupt can land inside the pool's submit() while it
    holds the pool's lock, and the pool's shutdown then waits on that lock for ever (seen
    in CI with 20,000 variants on a loaded machine). The note also stops the running
    variants at their next step (_mechkin.stop_all). Only the main thread receives
    SIGINT: elsewhere nothing is installed."""

    def __enter__(self):
        import signal
        import threading
        self.pending = False
        self.previous = None
        if threading.current_thread() is threading.main_thread():
            self.previous = signal.signal(signal.SIGINT, self._note)
        return self

    def _note(self, signum, frame):
        self.pending = True
        _mechkin.stop_all(True)

    def __exit__(self, *exc):
        import signal
        if self.previous is not None:
            signal.signal(signal.SIGINT, self.previous)
        return False


def _sweep_on_threads(model, variants, order, tol, threads):
    """The variants' summaries from local threads; on Ctrl-C the queued variants are
    dropped, the running ones stop at their next step, then KeyboardInterrupt is raised."""
    import concurrent.futures
    import os
    with concurrent.futures.ThreadPoolExecutor(max_workers=threads or os.cpu_count() or 1) as pool:
        with _DeferredInterrupt() as interrupt:
            futures = []
            for v in variants:
                if interrupt.pending:
                    break
                futures.append(pool.submit(_run_variant, model, v, order, tol))
            while not interrupt.pending and concurrent.futures.wait(futures, timeout=0.1).not_done:
                pass
            if interrupt.pending:
                for f in futures:
                    f.cancel()
                try:
                    concurrent.futures.wait(futures)
                finally:
                    _mechkin.stop_all(False)
                raise KeyboardInterrupt
            return [f.result() for f in futures]


def _sweep_frame(model, variants, summaries, order):
    """One row per variant: its parameters, status, message, rows, t_stop, max_condition,
    t_max_condition, then "<column> min" and "<column> max" per summarised column."""
    import pandas as pd
    names, units = model._core.sweep_columns(int(order))
    parameters = []
    for v in variants:
        parameters += [k for k in v if k not in parameters]
    frame = {k: [v.get(k, _np.nan) for v in variants] for k in parameters}
    for key in ("status", "message", "rows", "t_stop", "max_condition", "t_max_condition"):
        frame[key] = [s[key] for s in summaries]
    column_units = {"t_stop": "s", "t_max_condition": "s"}
    for k, (name, unit) in enumerate(zip(names, units)):
        for side in ("min", "max"):
            label = "%s %s" % (name, side)
            frame[label] = [s[side][k] if k < len(s[side]) else _np.nan for s in summaries]
            column_units[label] = unit
    df = pd.DataFrame(frame)
    df.attrs["units"] = column_units
    return df


def sweep(model, variants, client=None, order=1, tol=1e-10, threads=None, out=None, curves=None, chunk=None):
    """Runs every variant (a dict of parameter values, file units) of `model` and
    returns a pandas DataFrame with one row per variant, in order.

    Columns: the varied parameters; status ('complete', 'invalid', 'assembly',
    'refused', 'limit', 'singular', 'failed'); message (first line of why it is
    not complete, '' when it is); rows (rows run); t_stop (time of the last row of
    a run that stopped early, s; NaN when complete); max_condition and
    t_max_condition (s); then "<column> min" and "<column> max" over the motion for
    every output column (the bodies' without outputs) up to `order`, the column
    named as in a Motion of that order. Units are stated once, in
    df.attrs["units"] (the Motion's units of the column: the file's).

    order and tol are a RunRequest's (ValueError with the CLI's message when out of
    range). client: a dask.distributed Client — the variants are mapped over its
    workers (the model pickles as its file text and parameter values). Without one,
    local threads run them (the C++ core releases the GIL).

    Dataset sweeps (docs/datasets.md): with out=FOLDER and curves=[column names, e.g.
    "coupler_point.x"], every row of those columns of every variant is streamed into
    the HDF5 file FOLDER/sweep.h5 (read it with h5py), nothing held in memory, and its
    path is returned. With a client, each task writes its chunk of `chunk` variants
    (default: about four tasks per worker, at most 1000 variants) to its own part file
    FOLDER/part-NNNNN.h5 under a temporary name renamed when whole, so a task retried
    after its worker died rewrites its part; then sweep.h5 is made over the parts
    (virtual datasets, no data copied). FOLDER must be one the workers and the caller
    share (a cluster's shared file system)."""
    RunRequest(order=int(order), tol=float(tol)).validate()
    variants = [dict(v) for v in variants]
    if out is not None or curves is not None:
        return _sweep_dataset(model, variants, client, int(order), float(tol), threads, out, curves, chunk)
    if client is not None:
        shared = client.scatter(model, broadcast=True)
        futures = client.map(_run_variant, [shared] * len(variants), variants, order=order, tol=tol, pure=False)
        summaries = client.gather(futures)
    else:
        summaries = _sweep_on_threads(model, variants, order, tol, threads)
    return _sweep_frame(model, variants, summaries, order)


def _dataset_part(model, variants, first, total, curves, order, tol, path, identity):
    """One task of a dataset sweep on a cluster: its variants into its own part file."""
    return path, model._core.sweep_dataset(variants, first, 1, total, curves, order, tol, 1, path, identity)


def _sweep_dataset(model, variants, client, order, tol, threads, out, curves, chunk):
    import hashlib
    import os
    import uuid
    if out is None or not curves:
        raise ValueError("a dataset sweep needs both out=FOLDER and curves=[column names], "
                         "e.g. curves=['coupler_point.x', 'coupler_point.y']")
    curves = [curves] if isinstance(curves, str) else [str(c) for c in curves]
    keys = sorted(variants[0]) if variants else []
    for k, v in enumerate(variants):
        if sorted(v) != keys:
            raise ValueError("variant %d sets %s, the first sets %s: every variant must set the same parameters"
                             % (k, sorted(v), keys))
    variants = [{name: float(value) for name, value in v.items()} for v in variants]
    out = os.path.abspath(str(out))
    os.makedirs(out, exist_ok=True)
    target = os.path.join(out, "sweep.h5")
    digest = hashlib.sha1((model._core.text + _json.dumps(dict(model._core.overrides), sort_keys=True)).encode())
    identity = _json.dumps({"model_sha1": digest.hexdigest(), "order": order, "tol": tol, "curves": curves,
                            "variants": len(variants)}, sort_keys=True)
    if client is None:
        model._core.sweep_dataset(variants, 0, 1, len(variants), curves, order, tol, int(threads or 0), target,
                                  identity)
        return target
    workers = max(1, len(client.scheduler_info().get("workers", {})))
    size = int(chunk) if chunk else max(1, min(1000, -(-len(variants) // (4 * workers))))
    firsts = list(range(0, len(variants), size))
    paths = [os.path.join(out, "part-%05d.h5" % k) for k in range(len(firsts))]
    token = uuid.uuid4().hex[:8]
    shared = client.scatter(model, broadcast=True)
    futures = client.map(_dataset_part, [shared] * len(firsts), [variants[f:f + size] for f in firsts], firsts,
                         [len(variants)] * len(firsts), [curves] * len(firsts), [order] * len(firsts),
                         [tol] * len(firsts), paths, [identity] * len(firsts),
                         key=["mechkin-dataset-part-%s-%05d" % (token, k) for k in range(len(firsts))])
    client.gather(futures)
    _mechkin.merge_dataset(paths, target)
    return target
