#!/usr/bin/python3
"""Writes the importers' example mechanisms (issue 26) in URDF, SDFormat, MJCF and
FreeCAD's Document.xml from one description each:

  * an offset slider-crank (crank 40, rod 120, offset 10 mm, crank at 30 deg);
  * Theo Jansen's leg (the 13 "holy numbers", crank at 1 rad);
  * a Clavel Delta robot (three revolute arms, each forearm a parallelogram of two
    rods, universal at the elbow and spherical at the platform).

The text formats go to mechanisms/imported/, the Document.xml files to
tests/data/import/ (tests/importers zip them into .FCStd archives). Each mechanism is
described by its bodies and joints in the written pose (global frames, metres); each
emitter expresses that pose in its format's frames. The written pose is computed
here by the same constructions the tests check against (tests/importers/
closed_forms_test.cpp), so the files are assembled as written.

  /usr/bin/python3 tools/imported_examples.py [--check]   (--check: fail if a file differs)
"""
import math
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
I3 = np.eye(3)


class Mech:
    def __init__(self, name, note):
        self.name, self.note = name, note
        self.bodies = {}  # name -> (R, p): the body frame in the written pose
        self.joints = []  # dicts: name kind parent child R p tree

    def body(self, name, R, p):
        self.bodies[name] = (np.array(R, float), np.array(p, float))

    def joint(self, name, kind, parent, child, R, p, tree=True):
        self.joints.append(dict(name=name, kind=kind, parent=parent, child=child, R=np.array(R, float),
                                p=np.array(p, float), tree=tree))


def frame(m, b):
    return (I3, np.zeros(3)) if b == "ground" else m.bodies[b]


def rel(a, b):
    """b relative to a, both (R, p)."""
    return a[0].T @ b[0], a[0].T @ (b[1] - a[1])


def rpy(R):
    pitch = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    return math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])


def quat_wxyz(R):
    w = math.sqrt(max(0.0, 1 + R[0, 0] + R[1, 1] + R[2, 2])) / 2
    x = math.copysign(math.sqrt(max(0.0, 1 + R[0, 0] - R[1, 1] - R[2, 2])) / 2, R[2, 1] - R[1, 2])
    y = math.copysign(math.sqrt(max(0.0, 1 - R[0, 0] + R[1, 1] - R[2, 2])) / 2, R[0, 2] - R[2, 0])
    z = math.copysign(math.sqrt(max(0.0, 1 - R[0, 0] - R[1, 1] + R[2, 2])) / 2, R[1, 0] - R[0, 1])
    return w, x, y, z


def num(v):
    s = repr(float(v))
    return "0" if s in ("0.0", "-0.0") else s


def nums(vs):
    return " ".join(num(v) for v in vs)


def frame_with_z(z, x_hint):
    z = z / np.linalg.norm(z)
    x = x_hint - z * (x_hint @ z)
    x = x / np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def circle_point(P, rp, Q, rq, side):
    """The point at rp from P and rq from Q on the `side` (+1: left of P→Q) — planar."""
    d = Q - P
    L = np.linalg.norm(d)
    a = (rp * rp - rq * rq + L * L) / (2 * L)
    h = math.sqrt(rp * rp - a * a)
    e = d / L
    return P + a * e + side * h * np.array([-e[1], e[0]])


def sphere_point(C, r):
    """The lower intersection of three spheres of radius r about the rows of C."""
    ex = (C[1] - C[0]) / np.linalg.norm(C[1] - C[0])
    i = ex @ (C[2] - C[0])
    ey = C[2] - C[0] - i * ex
    ey = ey / np.linalg.norm(ey)
    ez = np.cross(ex, ey)
    d = np.linalg.norm(C[1] - C[0])
    j = ey @ (C[2] - C[0])
    x = d / 2
    y = (i * i + j * j) / (2 * j) - i * x / j
    z = math.sqrt(r * r - x * x - y * y)
    p = C[0] + x * ex + y * ey
    return min(p + z * ez, p - z * ez, key=lambda q: q[2])


# ---------------------------------------------------------------- mechanisms


def slider_crank():
    m = Mech("offset-slider-crank", "The offset slider-crank of mechanisms/offset-slider-crank.json (crank 40, "
             "rod 120, offset 10 mm; crank at 30 deg), in metres")
    r, l, e, th = 0.04, 0.12, 0.01, math.radians(30)
    B = np.array([r * math.cos(th), r * math.sin(th), 0])
    C = np.array([r * math.cos(th) + math.sqrt(l * l - (e - r * math.sin(th)) ** 2), e, 0])
    Rz = lambda a: np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    m.body("crank", Rz(th), [0, 0, 0])
    m.body("rod", Rz(math.atan2(C[1] - B[1], C[0] - B[0])), B)
    m.body("slider", I3, C)
    m.joint("bearing", "revolute", "ground", "crank", I3, [0, 0, 0])
    m.joint("crankpin", "revolute", "crank", "rod", I3, B)
    m.joint("guide", "prismatic", "ground", "slider", frame_with_z(np.array([1.0, 0, 0]), np.array([0, 0, -1.0])), C)
    m.joint("wristpin", "revolute", "rod", "slider", I3, C, tree=False)
    return m


# Jansen's numbers (mm) and the sides of the triangle constructions (+1: left of the
# first point → second point), as in tests/importers/closed_forms_test.cpp.
JANSEN = dict(a=38, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49, j=50, k=61.9, l=7.8, m=15)
JANSEN_SIDES = dict(W=+1, U=+1, V=-1, T=-1, S=-1)


def jansen_points(theta):
    n = {k: v * 1e-3 for k, v in JANSEN.items()}
    s = JANSEN_SIDES
    O, Y = np.zeros(2), np.array([-n["a"], -n["l"]])
    X = n["m"] * np.array([math.cos(theta), math.sin(theta)])
    W = circle_point(Y, n["b"], X, n["j"], s["W"])
    U = circle_point(Y, n["d"], W, n["e"], s["U"])
    V = circle_point(Y, n["c"], X, n["k"], s["V"])
    T = circle_point(U, n["f"], V, n["g"], s["T"])
    S = circle_point(T, n["h"], V, n["i"], s["S"])
    return dict(O=O, Y=Y, X=X, W=W, U=U, V=V, T=T, S=S)


def jansen():
    m = Mech("jansen-leg", "Theo Jansen's leg (a=38, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7, i=49, "
             "j=50, k=61.9, l=7.8, m=15 mm; crank O at 1 rad, pivot Y at (-a, -l)), in metres; ten revolute "
             "joints about z, three loops")
    P = {k: np.append(v, 0.0) for k, v in jansen_points(1.0).items()}
    for b, at in [("crank", "O"), ("rod_j", "X"), ("triangle_bde", "Y"), ("rod_k", "X"), ("rod_c", "Y"),
                  ("rod_f", "U"), ("triangle_ghi", "V")]:
        m.body(b, I3, P[at])
    for name, parent, child, at, tree in [("O", "ground", "crank", "O", True), ("X_j", "crank", "rod_j", "X", True),
                                          ("Y_bde", "ground", "triangle_bde", "Y", True),
                                          ("X_k", "crank", "rod_k", "X", True), ("Y_c", "ground", "rod_c", "Y", True),
                                          ("V_cg", "rod_c", "triangle_ghi", "V", True),
                                          ("U", "triangle_bde", "rod_f", "U", True),
                                          ("W", "rod_j", "triangle_bde", "W", False),
                                          ("V_kc", "rod_k", "rod_c", "V", False),
                                          ("T", "rod_f", "triangle_ghi", "T", False)]:
        m.joint(name, "revolute", parent, child, I3, P[at], tree)
    return m


# The Delta (m): base radius, upper arm, forearm, platform radius, half the
# parallelogram's width; legs at 0, 120, 240 deg; written arm angles (rad, down > 0).
DELTA = dict(base=0.2, arm=0.2, forearm=0.45, platform=0.05, half_width=0.03)
DELTA_WRITTEN = (0.5, 0.3, 0.6)


def delta_elbow(k, theta):
    g = DELTA
    phi = 2 * math.pi * k / 3
    radial = np.array([math.cos(phi), math.sin(phi), 0])
    return g["base"] * radial + g["arm"] * (math.cos(theta) * radial - math.sin(theta) * np.array([0, 0, 1.0]))


def delta(spherical_elbows=False):
    g = DELTA
    tag = "-ss" if spherical_elbows else ""
    m = Mech("delta" + tag, "A Clavel Delta robot: three revolute arms (shoulder_1..3 at 0, 120, 240 deg, base "
             "radius 0.2, arm 0.2 m) and three parallelogram forearms of two 0.45 m rods each, " +
             ("spherical" if spherical_elbows else "universal") + " at the elbow and spherical at the platform "
             "(radius 0.05 m, rods 0.06 m apart); arms written at 0.5, 0.3, 0.6 rad below the base plane")
    centres = []
    for k in range(3):
        phi = 2 * math.pi * k / 3
        radial = np.array([math.cos(phi), math.sin(phi), 0])
        centres.append(delta_elbow(k, DELTA_WRITTEN[k]) - g["platform"] * radial)
    P = sphere_point(np.array(centres), g["forearm"])
    m.body("platform", I3, P)
    for k in range(3):
        phi = 2 * math.pi * k / 3
        radial = np.array([math.cos(phi), math.sin(phi), 0])
        u = np.array([-math.sin(phi), math.cos(phi), 0])
        shoulder = g["base"] * radial
        Ru = frame_with_z(u, radial)
        arm = "arm_%d" % (k + 1)
        th = DELTA_WRITTEN[k]
        m.body(arm, frame_with_z(u, math.cos(th) * radial - math.sin(th) * np.array([0, 0, 1.0])), shoulder)
        m.joint("shoulder_%d" % (k + 1), "revolute", "ground", arm, Ru, shoulder)
        E = delta_elbow(k, th)
        for side, sgn in (("a", 1), ("b", -1)):
            top = E + sgn * g["half_width"] * u
            bottom = P + g["platform"] * radial + sgn * g["half_width"] * u
            d = (bottom - top) / np.linalg.norm(bottom - top)
            rod = "rod_%d%s" % (k + 1, side)
            m.body(rod, frame_with_z(d, u), top)
            b = np.cross(d, u)
            elbow = "ball" if spherical_elbows else "universal"
            m.joint("elbow_%d%s" % (k + 1, side), elbow, arm, rod, frame_with_z(u, b), top)
            m.joint("wrist_%d%s" % (k + 1, side), "ball", rod, "platform", I3, bottom, tree=(k == 0 and side == "a"))
    return m


# ---------------------------------------------------------------- URDF


def urdf_tree(m):
    """URDF link frames (= tree joint frames) and the joints with universal ones split in two."""
    links, joints = {"base": (I3, np.zeros(3))}, []
    for j in m.joints:
        if j["kind"] == "universal":
            cross = j["child"] + "_cross"
            joints.append(dict(j, name=j["name"] + "_1", kind="revolute", child=cross))
            joints.append(dict(j, name=j["name"] + "_2", kind="revolute", parent=cross,
                               R=j["R"] @ np.array([[0, 0, 1.0], [0, 1.0, 0], [-1.0, 0, 0]])))
        else:
            joints.append(dict(j))
    for j in joints:
        j["parent"] = "base" if j["parent"] == "ground" else j["parent"]
        if j["tree"] and j["kind"] != "ball":
            links[j["child"]] = (j["R"], j["p"])
    for b in list(m.bodies):
        links.setdefault(b, (I3, np.zeros(3)))  # a second root: at the origin
    return links, joints


def write_urdf(m):
    links, joints = urdf_tree(m)
    out = ['<?xml version="1.0"?>', "<!-- %s. Written by tools/imported_examples.py. URDF link frames are the "
           "joint frames; loops: a second <joint> naming a child again (revolute closures) and <loop_joint> "
           "(Drake's extension) for the spherical joints. -->" % m.note, '<robot name="%s">' % m.name]
    out += ['  <link name="%s"/>' % l for l in links]
    for j in joints:
        if j["kind"] == "ball":
            out.append('  <loop_joint name="%s" type="ball">' % j["name"])
            for tag, l in (("link1", j["parent"]), ("link2", j["child"])):
                R, p = rel(links[l], (j["R"], j["p"]))
                out.append('    <%s link="%s" xyz="%s" rpy="%s"/>' % (tag, l, nums(p), nums(rpy(R))))
            out.append("  </loop_joint>")
            continue
        R, p = rel(links[j["parent"]], (j["R"], j["p"]))
        kind = "continuous" if j["kind"] == "revolute" else j["kind"]
        out.append('  <joint name="%s" type="%s">' % (j["name"], kind))
        out.append('    <parent link="%s"/><child link="%s"/>' % (j["parent"], j["child"]))
        out.append('    <origin xyz="%s" rpy="%s"/>' % (nums(p), nums(rpy(R))))
        out.append('    <axis xyz="0 0 1"/>')
        if kind == "prismatic":
            out.append('    <limit lower="-1" upper="1" effort="100" velocity="1"/>')
        out.append("  </joint>")
    out.append("</robot>")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- SDFormat


def write_sdf(m):
    out = ['<?xml version="1.0"?>', "<!-- %s. Written by tools/imported_examples.py: links at their poses "
           "in the model, joint poses relative to the child link, kinematic loops as written. -->" % m.note,
           '<sdf version="1.9">', '  <model name="%s">' % m.name]
    for b, (R, p) in m.bodies.items():
        out.append('    <link name="%s"><pose>%s %s</pose></link>' % (b, nums(p), nums(rpy(R))))
    for j in m.joints:
        R, p = rel(frame(m, j["child"]), (j["R"], j["p"]))
        kind = "revolute" if j["kind"] == "revolute" else j["kind"]
        out.append('    <joint name="%s" type="%s">' % (j["name"], kind))
        out.append("      <pose>%s %s</pose>" % (nums(p), nums(rpy(R))))
        out.append("      <parent>%s</parent><child>%s</child>" % ("world" if j["parent"] == "ground" else j["parent"],
                                                                   j["child"]))
        if kind != "ball":
            out.append("      <axis><xyz>0 0 1</xyz></axis>")
        if kind == "universal":
            out.append("      <axis2><xyz>1 0 0</xyz></axis2>")
        out.append("    </joint>")
    out += ["  </model>", "</sdf>"]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- MJCF


def write_mjcf(m):
    children, closures = {}, []
    for j in m.joints:
        if j["tree"]:
            children.setdefault(j["parent"], []).append(j)
        else:
            closures.append(j)
    frames = {"ground": (I3, np.zeros(3))}
    out = ["<!-- %s. Written by tools/imported_examples.py: body frames at their first joint, loops closed by "
           "<equality><connect> (spherical joints: a revolute closure becomes a spherical one). -->" % m.note,
           '<mujoco model="%s">' % m.name, '  <compiler angle="radian"/>', "  <worldbody>"]

    def emit(parent, depth):
        for j in children.get(parent, []):
            F = (j["R"], j["p"])
            frames[j["child"]] = F
            R, p = rel(frames[parent], F)
            pad = "  " * depth
            out.append('%s<body name="%s" pos="%s" quat="%s">' % (pad, j["child"], nums(p), nums(quat_wxyz(R))))
            if j["kind"] == "universal":
                out.append('%s  <joint name="%s_1" type="hinge" axis="0 0 1"/>' % (pad, j["name"]))
                out.append('%s  <joint name="%s_2" type="hinge" axis="1 0 0"/>' % (pad, j["name"]))
            else:
                kind = {"revolute": "hinge", "prismatic": "slide", "ball": "ball"}[j["kind"]]
                axis = "" if kind == "ball" else ' axis="0 0 1"'
                out.append('%s  <joint name="%s" type="%s"%s/>' % (pad, j["name"], kind, axis))
            emit(j["child"], depth + 1)
            out.append("%s</body>" % pad)

    emit("ground", 2)
    out += ["  </worldbody>", "  <equality>"]
    for j in closures:
        anchor = rel(frames[j["parent"]], (j["R"], j["p"]))[1]
        out.append('    <connect name="%s" body1="%s" body2="%s" anchor="%s"/>' % (j["name"], j["parent"], j["child"],
                                                                                nums(anchor)))
    out += ["  </equality>", "</mujoco>"]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- FreeCAD Document.xml

FC_TYPES = ["Fixed", "Revolute", "Cylindrical", "Slider", "Ball", "Distance", "Parallel", "Perpendicular", "Angle",
            "RackPinion", "Screw", "Gears", "Belt"]


def fc_placement(R, p):
    w, x, y, z = quat_wxyz(R)
    q = np.array([x, y, z, w]) / math.sqrt(x * x + y * y + z * z + w * w)
    return ('<PropertyPlacement Px="%s" Py="%s" Pz="%s" Q0="%s" Q1="%s" Q2="%s" Q3="%s" A="0" Ox="0" Oy="0" Oz="1"/>'
            % tuple(num(v) for v in list(np.array(p) * 1000) + list(q)))


def fc_prop(name, kind, body):
    return '      <Property name="%s" type="%s">%s</Property>' % (name, kind, body)


def write_freecad(m):
    parts = {"Base": (I3, np.zeros(3))}
    names = {"ground": "Base"}
    for b, F in m.bodies.items():
        names[b] = b.title().replace("_", "")
        parts[names[b]] = F
    labels = {"Base": "base"}
    labels.update({names[b]: b for b in m.bodies})
    joints = []
    for j in m.joints:
        if j["kind"] == "universal":  # no universal joint in FreeCAD: a cross part between two revolutes
            cross = names[j["child"]] + "Cross"
            parts[cross], labels[cross] = (j["R"], j["p"]), j["child"] + "_cross"
            joints.append(dict(j, name=j["name"] + "_1", kind="revolute", child=cross, parent=names[j["parent"]]))
            joints.append(dict(j, name=j["name"] + "_2", kind="revolute", parent=cross, child=names[j["child"]],
                               R=j["R"] @ np.array([[0, 0, 1.0], [0, 1.0, 0], [-1.0, 0, 0]])))
        else:
            joints.append(dict(j, parent=names[j["parent"]], child=names[j["child"]]))
    objs = [("Assembly", "Assembly::AssemblyObject")] + [(p, "Part::Feature") for p in parts]
    objs += [("GroundedJoint", "App::FeaturePython")] + [("Joint%03d" % k, "App::FeaturePython") for k in range(len(joints))]
    out = ["<?xml version='1.0' encoding='utf-8'?>",
           "<!-- Document.xml of a FreeCAD 1.x Assembly (mm): %s. Written by tools/imported_examples.py the way "
           "FreeCAD's Assembly workbench saves joints: JointType a custom enumeration, references as "
           "[Assembly, [Part.Element, Part.Vertex]], Placement1/2 relative to the referenced part (offsets "
           "included), Activated. tests/importers zip it into an .FCStd. -->" % m.note,
           '<Document SchemaVersion="4" ProgramVersion="1.0.0" FileVersion="1">', '  <Objects Count="%d">' % len(objs)]
    out += ['    <Object type="%s" name="%s"/>' % (t, n) for n, t in objs]
    out += ["  </Objects>", '  <ObjectData Count="%d">' % len(objs), '    <Object name="Assembly">',
            '      <Properties Count="1">', fc_prop("Placement", "App::PropertyPlacement", fc_placement(I3, [0, 0, 0])),
            "      </Properties>", "    </Object>"]
    for p, F in parts.items():
        out += ['    <Object name="%s">' % p, '      <Properties Count="2">',
                fc_prop("Label", "App::PropertyString", '<String value="%s"/>' % labels[p]),
                fc_prop("Placement", "App::PropertyPlacement", fc_placement(*F)), "      </Properties>", "    </Object>"]
    out += ['    <Object name="GroundedJoint">', '      <Properties Count="2">',
            fc_prop("Label", "App::PropertyString", '<String value="GroundedJoint"/>'),
            fc_prop("ObjectToGround", "App::PropertyLink", '<Link value="Base"/>'), "      </Properties>", "    </Object>"]
    enum = "".join('<Enum value="%s"/>' % t for t in FC_TYPES)
    for k, j in enumerate(joints):
        t = FC_TYPES.index({"revolute": "Revolute", "prismatic": "Slider", "ball": "Ball"}[j["kind"]])
        out += ['    <Object name="Joint%03d">' % k, '      <Properties Count="9">',
                fc_prop("Label", "App::PropertyString", '<String value="%s"/>' % j["name"]),
                fc_prop("JointType", "App::PropertyEnumeration", '<Integer value="%d" CustomEnum="true"/>'
                        '<CustomEnumList count="%d">%s</CustomEnumList>' % (t, len(FC_TYPES), enum)),
                fc_prop("Activated", "App::PropertyBool", '<Bool value="true"/>')]
        for n, part in (("1", j["parent"]), ("2", j["child"])):
            out.append(fc_prop("Reference" + n, "App::PropertyXLinkSubHidden",
                               '<XLinkSub file="" name="Assembly" count="2"><Sub value="%s.Vertex1"/>'
                               '<Sub value="%s.Vertex1"/></XLinkSub>' % (part, part)))
            out.append(fc_prop("Placement" + n, "App::PropertyPlacement",
                               fc_placement(*rel(parts[part], (j["R"], j["p"])))))
            out.append(fc_prop("Offset" + n, "App::PropertyPlacement", fc_placement(I3, [0, 0, 0])))
        out += ["      </Properties>", "    </Object>"]
    out += ["  </ObjectData>", "</Document>"]
    return "\n".join(out) + "\n"


def outputs():
    files = {}
    for m in (slider_crank(), jansen(), delta()):
        base = os.path.join(ROOT, "mechanisms", "imported", m.name)
        if m.name != "offset-slider-crank":  # its URDF is written by hand (a second parent)
            files[base + ".urdf"] = write_urdf(m)
        files[base + ".sdf"] = write_sdf(m)
        files[base + ".xml"] = write_mjcf(m)
        files[os.path.join(ROOT, "tests", "data", "import", m.name + "-Document.xml")] = write_freecad(m)
    files[os.path.join(ROOT, "tests", "data", "import", "delta-ss.xml")] = write_mjcf(delta(spherical_elbows=True))
    return files


def main():
    check = "--check" in sys.argv[1:]
    stale = []
    for path, text in outputs().items():
        old = open(path).read() if os.path.exists(path) else None
        if old != text:
            stale.append(path)
            if not check:
                with open(path, "w") as f:
                    f.write(text)
    for p in stale:
        print(("differs: " if check else "wrote ") + os.path.relpath(p, ROOT))
    return 1 if check and stale else 0


if __name__ == "__main__":
    sys.exit(main())
