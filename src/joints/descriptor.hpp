// A joint type as data (issue 32): what the file says for it, how its frames are
// built, the primitive equations it is made of (constraints.md §5), its
// coordinates for outputs, drivers and limits, how mobility may loosen it and how
// the viewer draws it. Every layer above reads these fields; none names a joint.
// The recipe for a new joint is docs/joints.md.
#pragma once

#include <string>
#include <vector>

namespace mechkin {

/// Which of the file's keys give the joint's frame (constraints.md §4), and so its
/// geometry keys (JointFrameKeys): the same frame is fixed in both bodies unless said.
enum class JointFrameRule {
  Axis,       // "origin", "axis": h along the axis
  Normal,     // "origin", "normal": h along the plane's normal
  CrossAxes,  // "origin", "axis1", "axis2": body1's h = axis1, body2's h = axis2 (f = axis1)
  Point,      // "origin" only: the frame's axes are the global ones
  TwoPoints,  // "point1" on body1, "point2" on body2: the frames are the two points
};

/// A scalar of the file beside the geometry.
enum class JointScalar {
  None,
  Pitch,   // "pitch" (required): metres per revolution, into Joint::pitch
  Length,  // "length" (optional; else the design distance of the two points), into Joint::length
};

enum class FrameAxis { F, G, H };

/// The primitive families of constraints.md §3 a joint is built from.
enum class JointPrimitive {
  Spherical,  // Φ^SPH(P_i, P_j), §3.1: 3 rows
  Distance,   // Φ^SPH_SPH(P_i, P_j) = L, §3.2
  Dot1,       // Φ^DOT_1(a_i, a_j), §3.3: vector `first` of body1's frame ⟂ vector `second` of body2's
  Dot2,       // Φ^DOT_2(a_i, d_ij), §3.4: vector `first` of body1's frame ⟂ P_j − P_i
  Screw,      // Φ^SDA with the joint's pitch, §3.10
};

/// One primitive of a joint, with its rows' descriptions in joint vocabulary
/// (diagnostics: "joint `crank` (revolute): rotation about its frame's g axis").
struct JointEquation {
  JointPrimitive primitive = JointPrimitive::Spherical;
  FrameAxis first = FrameAxis::H, second = FrameAxis::H;
  std::vector<std::string> rows;  // one description a row
};

/// What a joint output reports (docs/format.md "outputs"), and which coordinate
/// branch hints, velocity ratios and the assembly read.
enum class JointCoordinates {
  None,               // a distance link: its length does not change
  Angle,              // θ about h (one column)
  Slide,              // s along h (one column)
  AngleAndSlide,      // ".angle", ".slide"
  TwoAngles,          // ".angle1", ".angle2" (a Hooke joint's cross axes)
  PlaneSlidesAndAngle,  // ".slide1", ".slide2", ".angle" about the normal
  Orientation,        // body2 relative to body1 in a rotation sequence ("sequence")
};

/// The coordinate "limits" bound (none: the joint takes no "limits").
enum class JointLimit { None, Angle, Slide };

/// The joint in a planar Grübler count (constraints.md §6.1): a spatial joint makes
/// the mechanism spatial.
enum class PlanarRole {
  Spatial,
  Turn,   // axis along the plane's normal, removes 2 in the plane
  Slide,  // axis in the plane, removes 2
  Plane,  // normal along the plane's normal: removes nothing in the plane
  Link,   // a distance link: a higher pair, removes 1
};

struct JointDescriptor {
  std::string name;  // the file's "type"
  JointFrameRule frames = JointFrameRule::Axis;
  JointScalar scalar = JointScalar::None;
  std::vector<JointEquation> equations;  // in row order
  JointCoordinates coordinates = JointCoordinates::None;
  bool turns = false;   // a rotation about h: rotation drivers, couplers' rotations
  bool slides = false;  // a translation along h: translation drivers, couplers' slides
  JointLimit limit = JointLimit::None;
  PlanarRole planar = PlanarRole::Spatial;
  // Joint types mobility may put in its place to remove redundant equations
  // (constraints.md §6.3): each keeps the joint's frames and removes fewer equations.
  std::vector<std::string> relaxations;
  std::string glyph;  // how the viewer draws it (src/io/viewer/app.js "glyphs")

  /// Equations the joint removes (its rows), the Grübler count's share (§6.1).
  int Rows() const;
  /// The joint holds its two frames' origins together (a spherical primitive) or at a
  /// fixed distance: a side of the polygon a loop of such joints makes.
  bool HoldsPoints() const;
  /// The keys of its geometry in the file: required, then optional (after the common ones).
  std::vector<std::string> RequiredKeys() const;
  std::vector<std::string> OptionalKeys() const;
  /// Besides "marker1" and "marker2" on markers: required, then optional.
  std::vector<std::string> MarkerRequiredKeys() const;
  std::vector<std::string> MarkerOptionalKeys() const;
};

/// The rows of the two recurring pairs of constraints.md §5 and of Φ^SPH, for
/// descriptors: parallel-1 keeps h_j ∥ h_i, parallel-2 keeps P_j on the axis of i.
JointEquation SphericalEquation();
std::vector<JointEquation> ParallelOne();
std::vector<JointEquation> ParallelTwo();

}  // namespace mechkin
