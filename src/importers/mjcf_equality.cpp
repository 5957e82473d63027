// MJCF <equality> (docs/import.md "MJCF"): MuJoCo's soft equality constraints read as
// exact ones — <connect> a spherical joint (its anchor in body1; or two sites that
// coincide), <weld> a fixed connection, <joint> a coupling of two joint coordinates
// (linear polycoef only). solref/solimp (the softness) are not kinematic.
#include <cstring>

#include "importers/mjcf.hpp"

namespace mechkin::importers::mjcf {

using tinyxml2::XMLElement;

namespace {

// body1 / body2 (absent: the world) → link names; false with an error.
bool Bodies(const XMLElement* e, Reader* r, std::string* b1, std::string* b2) {
  const char* a = RequiredAttribute(e, "body1", r->g);
  if (!a) return false;
  const char* b = e->Attribute("body2");
  *b1 = a, *b2 = b ? b : "world";
  for (const std::string& n : {*b1, *b2})
    if (!r->g->FindLink(n)) return r->g->Error(e, "body '" + n + "' is not defined", "fix the body name"), false;
  if (*b1 == *b2) return r->g->Error(e, "body1 and body2 are the same body", "join two bodies"), false;
  return true;
}

std::string NameOf(const XMLElement* e, const char* kind) {
  const char* n = e->Attribute("name");
  return n ? n : std::string(kind) + std::to_string(e->GetLineNum());
}

void ReadConnect(const XMLElement* e, Reader* r) {
  Graph* g = r->g;
  Joint j;
  j.kind = Kind::Spherical;
  j.name = NameOf(e, "connect");
  j.place = g->PlaceOf(e);
  if (e->Attribute("site1") || e->Attribute("site2")) {
    const char* s1 = RequiredAttribute(e, "site1", g);
    const char* s2 = RequiredAttribute(e, "site2", g);
    if (!s1 || !s2) return;
    for (const char* s : {s1, s2})
      if (!r->sites.count(s)) return g->Error(e, std::string("site '") + s + "' is not defined", "fix the site name");
    const Site &a = r->sites.at(s1), &b = r->sites.at(s2);
    j.parent = a.link, j.child = b.link;
    j.in_parent.p = a.pos, j.in_child.p = b.pos;
    if (j.parent == j.child) return g->Error(e, "both sites are on body '" + a.link + "'", "join two bodies");
  } else {
    double anchor[3];
    if (!Bodies(e, r, &j.parent, &j.child) || !ReadNumbers(e, "anchor", 3, anchor, g)) return;
    j.in_parent.p = Vec3(anchor[0], anchor[1], anchor[2]);
    j.in_child = g->FindLink(j.child)->world.Inverse() * g->FindLink(j.parent)->world * j.in_parent;
  }
  g->AddJoint(std::move(j), e);
}

void ReadWeld(const XMLElement* e, Reader* r) {
  Graph* g = r->g;
  Joint j;
  j.kind = Kind::Fixed;
  j.name = NameOf(e, "weld");
  j.place = g->PlaceOf(e);
  if (e->Attribute("site1") || e->Attribute("site2"))
    return g->Error(e, "a site-based <weld> is not supported", "weld the two bodies (body1, body2) instead");
  if (!Bodies(e, r, &j.parent, &j.child)) return;
  double rel[7] = {0, 1, 0, 0, 0, 0, 0};
  if (!ReadOptionalNumbers(e, "relpose", 7, rel, g)) return;
  const Eigen::Quaterniond q(rel[3], rel[4], rel[5], rel[6]);
  if (q.norm() > 0) {  // a pose of its own (all-zero quaternion: the written pose)
    const Pose written = g->FindLink(j.parent)->world.Inverse() * g->FindLink(j.child)->world;
    const Pose given{q.normalized().toRotationMatrix(), Vec3(rel[0], rel[1], rel[2])};
    const double miss = (written.p - given.p).norm() + (written.R - given.R).norm();
    if (miss > 1e-9)
      return g->Error(e, "relpose differs from the bodies' written relative pose (by " + std::to_string(miss) + ")",
                      "write the bodies where the weld holds them, or omit relpose");
  }
  g->AddJoint(std::move(j), e);
}

// y − y0 = a0 + a1 (x − x0): the coordinates q − ref are mechkin's, so y' − a1 x' = a0.
void ReadJointEquality(const XMLElement* e, Reader* r) {
  Graph* g = r->g;
  const char* j1 = RequiredAttribute(e, "joint1", g);
  if (!j1) return;
  const char* j2 = e->Attribute("joint2");
  double c[5] = {0, 1, 0, 0, 0};
  if (!ReadOptionalNumbers(e, "polycoef", 5, c, g)) return;
  if (!j2)
    return g->Error(e, "a joint equality without joint2 locks joint '" + std::string(j1) + "': not supported",
                    "drive the joint with a constant (--drive " + std::string(j1) + "=VALUE) instead");
  if (c[2] != 0 || c[3] != 0 || c[4] != 0)
    return g->Error(e, "a nonlinear polycoef (a2, a3 or a4 not 0) is not supported: mechkin couplings are linear",
                    "keep a0 and a1 only");
  for (const char* n : {j1, j2})
    if (!r->joints.count(n)) return g->Error(e, std::string("joint '") + n + "' is not defined", "fix the joint name");
  g->couplings.push_back({NameOf(e, "coupling"), {j1, j2}, {1.0, -c[1]}, c[0], g->PlaceOf(e)});
}

}  // namespace

void ReadEquality(const XMLElement* equality, Reader* r) {
  for (const XMLElement* e = equality->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (const char* active = e->Attribute("active"); active && !std::strcmp(active, "false")) {
      r->g->Warn(e, "inactive (active=\"false\"): not imported");
      continue;
    }
    if (tag == "connect") ReadConnect(e, r);
    else if (tag == "weld") ReadWeld(e, r);
    else if (tag == "joint") ReadJointEquality(e, r);
    else
      r->g->Error(e, "equality <" + tag + "> is not supported",
                  tag == "tendon" ? "a tendon equality needs tendon lengths, which mechkin does not model"
                                  : "use connect, weld or joint");
  }
}

}  // namespace mechkin::importers::mjcf
