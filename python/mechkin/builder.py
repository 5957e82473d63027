"""mechkin.Mechanism: a mechanism built in Python, element by element.

The builder writes the mechanism file's own form (docs/format.md), so what it
builds is exactly what a file with the same content says: `to_dict()` is that
file as a dict, `compile()` hands it to the C++ reader and compiler (the same
diagnostics, with JSON pointers into `to_dict()`), and `json.dump(m.to_dict(), f)`
writes a file `mechkin run` reads.

    m = mechkin.Mechanism("four-bar", units={"length": "mm", "angle": "deg"})
    m.add_parameter("crank", 40)
    m.add_marker("ground", "bearing", point=[0, 0, 0])
    m.add_body("crank")
    m.add_marker("crank", "bearing", point=[0, 0, 0])
    m.add_marker("crank", "pin", point=["crank", 0, 0])
    m.add_joint("bearing", "revolute", "ground", "crank", marker1="bearing", marker2="bearing")
    ...
    m.add_driver("motor", "rotation", joint="bearing", function="360*t")
    model = m.compile()             # a mechkin.Model; m.compile(crank=45) overrides a parameter

Numbers may be parameter expressions (strings) wherever the file allows them.
Names are checked as they are added (a duplicate raises ValueError at once);
everything else is checked by compile(), which raises FormatError.
"""
import copy as _copy

_COUPLER_TYPES = ("gear", "belt", "rack_pinion", "screw_coupling", "coupling")
_JOINT_TYPES = ("revolute", "prismatic", "screw", "cylindrical", "universal", "spherical", "planar", "distance")
_GROUND = "ground"


def _vector(value, what):
    """A 3-vector of numbers or expression strings, as a list."""
    items = list(value)
    if len(items) != 3:
        raise ValueError("%s must have 3 components, got %d" % (what, len(items)))
    return items


def _drop_none(fields):
    return {k: v for k, v in fields.items() if v is not None}


class Mechanism:
    """A mechanism under construction, in the file's form (see the module doc).

    Methods add one element each and return its name: add_parameter, add_body,
    add_marker, add_joint, add_coupler (add_gear), add_driver, add_output, add_load; set_analysis,
    set_expect, set_gravity, set_view. to_dict() gives the file as a dict,
    compile(**parameters) the mechkin.Model."""

    def __init__(self, name, description=None, units=None):
        self._file = {"mechkin": 1, "name": str(name)}
        if description is not None:
            self._file["description"] = str(description)
        if units is not None:
            self._file["units"] = dict(units)
        self._bodies, self._joints, self._drivers, self._outputs, self._loads = [], [], [], [], []
        self._couplers = []
        self._parameters, self._ground_markers = {}, {}
        self._body_index = {}
        self._names = {"joint": set(), "driver": set(), "output": set(), "load": set(), "coupler": set()}

    # -- elements --------------------------------------------------------------
    def add_parameter(self, name, value, tolerance=None, min=None, max=None, description=None):
        """A named number (or an expression of earlier ones) the geometry may use."""
        self._unique(name, self._parameters, "parameter")
        extra = _drop_none(dict(tolerance=tolerance, min=min, max=max, description=description))
        self._parameters[name] = dict(value=value, **extra) if extra else value
        return name

    def add_body(self, name, position=None, orientation=None, inertia=None, shape=None, markers=None):
        """A moving body. position/orientation: its pose at the design configuration
        (for bodies placed by markers, a starting sketch); markers: {name: marker}."""
        if name == _GROUND:
            raise ValueError("'ground' is the fixed body; give its markers with add_marker('ground', ...)")
        self._unique(name, self._body_index, "body")
        body = {"name": name}
        if position is not None:
            body["position"] = _vector(position, "body '%s' position" % name)
        body.update(_drop_none(dict(orientation=orientation, inertia=inertia, shape=shape)))
        self._body_index[name] = len(self._bodies)
        self._bodies.append(body)
        for marker, fields in (markers or {}).items():
            self.add_marker(name, marker, **fields)
        return name

    def add_marker(self, body, name, point, axis=None, x_axis=None):
        """A frame fixed in `body` ('ground' for ground), in that body's coordinates:
        its origin `point`, its z `axis` and optionally `x_axis` fixing its x."""
        table = self._markers_of(body)
        self._unique(name, table, "marker on '%s'" % body)
        marker = {"point": _vector(point, "marker '%s' point" % name)}
        if axis is not None:
            marker["axis"] = _vector(axis, "marker '%s' axis" % name)
        if x_axis is not None:
            marker["x_axis"] = _vector(x_axis, "marker '%s' x_axis" % name)
        table[name] = marker
        return name

    def add_joint(self, name, type, body1, body2, **geometry):
        """A joint of `type` between body1 and body2: either on two markers
        (marker1=, marker2=) or with global geometry (origin=, axis=, axis1=,
        axis2=, normal=, point1=, point2=), plus pitch= (screw) or length= (distance)."""
        if type not in _JOINT_TYPES:
            raise ValueError("unknown joint type '%s'; one of %s" % (type, ", ".join(_JOINT_TYPES)))
        self._unique(name, self._names["joint"], "joint")
        self._names["joint"].add(name)
        joint = {"name": name, "type": type, "body1": body1, "body2": body2}
        joint.update(_drop_none(geometry))
        self._joints.append(joint)
        return name

    def add_coupler(self, name, type, **fields):
        """A coupler between joint coordinates (docs/format.md, couplers): 'gear' or
        'belt' (joint1=, joint2=, ratio=: θ₂ = ratio·θ₁), 'rack_pinion' (joint1= the
        pinion, joint2= the rack, pitch_radius=), 'screw_coupling' (joint1=, joint2=,
        pitch=) or 'coupling' (joints=[...], coefficients=[...], constant=, coordinates=)."""
        if type not in _COUPLER_TYPES:
            raise ValueError("unknown coupler type '%s'; one of %s" % (type, ", ".join(_COUPLER_TYPES)))
        self._unique(name, self._names["coupler"], "coupler")
        self._names["coupler"].add(name)
        coupler = {"name": name, "type": type}
        coupler.update(_drop_none(fields))
        self._couplers.append(coupler)
        return name

    def add_gear(self, name, joint1, joint2, ratio, pitch_radius=None, pressure_angle=None):
        """A gear pair: θ(joint2) = ratio · θ(joint1) (negative for an external mesh).
        With pitch_radius (joint1's gear, length unit) and optionally pressure_angle
        (angle unit, default 20°) the bearings' reactions include the tooth force."""
        return self.add_coupler(name, "gear", joint1=joint1, joint2=joint2, ratio=ratio, pitch_radius=pitch_radius,
                                pressure_angle=pressure_angle)

    def add_driver(self, name, type, function, **where):
        """A driver: type 'rotation'/'translation' of a joint (joint=), of a body
        (body=, axis=), a 'distance' between points, ...; function of t (text or table)."""
        self._unique(name, self._names["driver"], "driver")
        self._names["driver"].add(name)
        driver = {"name": name, "type": type}
        driver.update(_drop_none(where))
        driver["function"] = function
        self._drivers.append(driver)
        return name

    def add_output(self, name, type, **fields):
        """An output column group: 'point' (body=, point= or marker=), 'joint' (joint=), ..."""
        self._unique(name, self._names["output"], "output")
        self._names["output"].add(name)
        self._outputs.append(dict(name=name, type=type, **_drop_none(fields)))
        return name

    def add_load(self, name, type, **fields):
        """An applied force, torque or spring-damper (docs/format.md, loads)."""
        self._unique(name, self._names["load"], "load")
        self._names["load"].add(name)
        self._loads.append(dict(name=name, type=type, **_drop_none(fields)))
        return name

    # -- sections --------------------------------------------------------------
    def set_analysis(self, start=None, end=None, steps=None, branch=None):
        self._file["analysis"] = _drop_none(dict(start=start, end=end, steps=steps, branch=branch))

    def set_expect(self, **expect):
        self._file["expect"] = dict(expect)

    def set_gravity(self, gravity):
        self._file["gravity"] = _vector(gravity, "gravity")

    def set_view(self, **view):
        self._file["view"] = dict(view)

    # -- results ---------------------------------------------------------------
    def to_dict(self):
        """The mechanism file as a dict (a deep copy: editing it leaves the builder alone)."""
        out = {k: self._file[k] for k in ("mechkin", "name", "description", "units") if k in self._file}
        if self._parameters:
            out["parameters"] = self._parameters
        if self._ground_markers:
            out["ground"] = {"markers": self._ground_markers}
        out["bodies"] = self._bodies
        out["joints"] = self._joints
        if self._couplers:
            out["couplers"] = self._couplers
        if self._drivers:
            out["drivers"] = self._drivers
        for key in ("gravity", "analysis"):
            if key in self._file:
                out[key] = self._file[key]
        if self._outputs:
            out["outputs"] = self._outputs
        if self._loads:
            out["loads"] = self._loads
        for key in ("expect", "view"):
            if key in self._file:
                out[key] = self._file[key]
        return _copy.deepcopy(out)

    def compile(self, **parameters):
        """The mechkin.Model (raises FormatError naming the JSON pointer of each
        problem in to_dict()); keyword arguments override parameter values."""
        from . import loads
        model = loads(self.to_dict(), source="<Mechanism %s>" % self._file["name"])
        return model.with_parameters(**parameters) if parameters else model

    def __repr__(self):
        return "Mechanism(%r, %d bodies, %d joints, %d drivers)" % (
            self._file["name"], len(self._bodies), len(self._joints), len(self._drivers))

    # -- helpers ---------------------------------------------------------------
    def _markers_of(self, body):
        if body == _GROUND:
            return self._ground_markers
        if body not in self._body_index:
            raise ValueError("unknown body '%s': add it with add_body first" % body)
        return self._bodies[self._body_index[body]].setdefault("markers", {})

    @staticmethod
    def _unique(name, existing, what):
        if not isinstance(name, str) or not name:
            raise ValueError("a %s needs a non-empty name" % what)
        if name in existing:
            raise ValueError("duplicate %s name '%s'" % (what, name))
