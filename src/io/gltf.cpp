// glTF 2.0 export of a motion (https://registry.khronos.org/glTF/specs/2.0/):
// one node per body plus a ground node, each body a mesh of thin square bars
// from the centroid of its points to each point (non-metallic materials), and
// one animation with a translation and a rotation channel per body (LINEAR).
// Lengths in metres, as glTF requires.
#include <array>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "io/output_file.hpp"
#include "io/viewer.hpp"

namespace mechkin {
namespace {

using nlohmann::json;

struct Mesh {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
};

// A square bar of half-width w from a to b: 8 corners, 12 triangles.
void AddBar(const Vec3& a, const Vec3& b, double w, Mesh* mesh) {
  Vec3 d = b - a;
  if (!(d.norm() > 0)) d = Vec3::UnitX() * w;
  const Vec3 u = d.normalized();
  const Vec3 e1 = (std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(u).normalized() * w, e2 = u.cross(e1);
  const uint32_t base = static_cast<uint32_t>(mesh->positions.size() / 3);
  for (const Vec3& end : {a, Vec3(a + d)})
    for (const Vec3& c : {Vec3(-e1 - e2), Vec3(e1 - e2), Vec3(e1 + e2), Vec3(-e1 + e2)})
      for (int k = 0; k < 3; ++k) mesh->positions.push_back(static_cast<float>((end + c)[k]));
  static const uint32_t kFaces[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                      1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  for (uint32_t f : kFaces) mesh->indices.push_back(base + f);
}

Mesh BodyMesh(const std::vector<Vec3>& pts, double w) {
  Mesh m;
  Vec3 c = Vec3::Zero();
  for (const auto& p : pts) c += p / static_cast<double>(pts.size());
  if (pts.size() == 2) AddBar(pts[0], pts[1], w, &m);
  else
    for (const auto& p : pts) AddBar(c, p, w, &m);
  if (pts.size() <= 1) AddBar(c - Vec3(w, 0, 0), c + Vec3(w, 0, 0), w, &m);
  return m;
}

class Buffer {
 public:
  // Appends data as a new bufferView (4-byte aligned); returns its index.
  int View(const void* data, size_t bytes, json* views, int target = 0) {
    while (bytes_.size() % 4) bytes_.push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + bytes);
    views->push_back(v);
    return static_cast<int>(views->size()) - 1;
  }
  std::vector<unsigned char>& bytes() { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
};

// A float accessor of `type` (SCALAR, VEC3, VEC4) with min/max per component.
int FloatAccessor(const std::vector<float>& v, int comps, const char* type, Buffer* buf, json* doc, int target = 0) {
  const int view = buf->View(v.data(), v.size() * sizeof(float), &(*doc)["bufferViews"], target);
  json mn = json::array(), mx = json::array();
  for (int c = 0; c < comps; ++c) {
    float lo = INFINITY, hi = -INFINITY;
    for (size_t k = c; k < v.size(); k += comps) lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
    mn.push_back(lo), mx.push_back(hi);
  }
  (*doc)["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", v.size() / comps},
                                 {"type", type}, {"min", mn}, {"max", mx}});
  return static_cast<int>((*doc)["accessors"].size()) - 1;
}

int AddMesh(const Mesh& mesh, int material, Buffer* buf, json* doc) {
  const int pos = FloatAccessor(mesh.positions, 3, "VEC3", buf, doc, 34962);
  const int view = buf->View(mesh.indices.data(), mesh.indices.size() * 4, &(*doc)["bufferViews"], 34963);
  (*doc)["accessors"].push_back({{"bufferView", view}, {"componentType", 5125}, {"count", mesh.indices.size()}, {"type", "SCALAR"}});
  const int idx = static_cast<int>((*doc)["accessors"].size()) - 1;
  (*doc)["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", material}}}}});
  return static_cast<int>((*doc)["meshes"].size()) - 1;
}

int AddMaterial(int k, json* doc) {
  static const float kColors[][3] = {{0.12f, 0.47f, 0.71f}, {0.84f, 0.15f, 0.16f}, {0.17f, 0.63f, 0.17f},
                                     {1.0f, 0.5f, 0.05f},   {0.58f, 0.4f, 0.74f},  {0.55f, 0.34f, 0.29f}};
  const float* c = k < 0 ? nullptr : kColors[k % 6];
  const json color = c ? json::array({c[0], c[1], c[2], 1.0}) : json::array({0.6, 0.6, 0.6, 1.0});
  (*doc)["materials"].push_back({{"name", k < 0 ? "ground" : "body" + std::to_string(k)},
                                 {"pbrMetallicRoughness", {{"baseColorFactor", color}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.7}}}});
  return static_cast<int>((*doc)["materials"].size()) - 1;
}

// Per body, the table's poses as keyframes: translations (m) and rotations (x, y, z, w).
void AddAnimation(const Model& model, const Motion& m, Buffer* buf, json* doc) {
  const int order = m.layout().options().order;
  const double to_m = 1 / m.layout().length_factor();
  std::vector<float> times;
  for (int r = 0; r < m.rows(); ++r) times.push_back(static_cast<float>(m.at(r, 0)));
  const int input = FloatAccessor(times, 1, "SCALAR", buf, doc);
  json samplers = json::array(), channels = json::array();
  for (int b = 0; b < model.num_bodies(); ++b) {
    const int x = m.layout().Find(Quantity::BodyPosition, b, 0, 0), e = m.layout().Find(Quantity::EulerParameter, b, 0, 0);
    std::vector<float> tr, rot;
    for (int r = 0; r < m.rows(); ++r) {
      for (int a = 0; a < 3; ++a) tr.push_back(static_cast<float>(m.at(r, x + a * (order + 1)) * to_m));
      for (int a : {1, 2, 3, 0}) rot.push_back(static_cast<float>(m.at(r, e + a)));
    }
    samplers.push_back({{"input", input}, {"output", FloatAccessor(tr, 3, "VEC3", buf, doc)}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", b + 1}, {"path", "translation"}}}});
    samplers.push_back({{"input", input}, {"output", FloatAccessor(rot, 4, "VEC4", buf, doc)}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", b + 1}, {"path", "rotation"}}}});
    (*doc)["nodes"][b + 1]["translation"] = {tr[0], tr[1], tr[2]};
    (*doc)["nodes"][b + 1]["rotation"] = {rot[0], rot[1], rot[2], rot[3]};
  }
  (*doc)["animations"] = {{{"name", "motion"}, {"samplers", samplers}, {"channels", channels}}};
}

std::string Base64(const std::vector<unsigned char>& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    const uint32_t v = in[i] << 16 | (i + 1 < in.size() ? in[i + 1] << 8 : 0) | (i + 2 < in.size() ? in[i + 2] : 0);
    out += k[v >> 18 & 63];
    out += k[v >> 12 & 63];
    out += i + 1 < in.size() ? k[v >> 6 & 63] : '=';
    out += i + 2 < in.size() ? k[v & 63] : '=';
  }
  return out;
}

void Put32(std::string* s, uint32_t v) { s->append(reinterpret_cast<const char*>(&v), 4); }  // little-endian host

}  // namespace

bool WriteGltf(const Model& model, const Motion& motion, const std::string& path, OutputFile* file, std::string* error) {
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "mechkin"}}}, {"scene", 0}, {"nodes", json::array()},
              {"meshes", json::array()}, {"materials", json::array()}, {"accessors", json::array()},
              {"bufferViews", json::array()}};
  Buffer buf;
  const double w = 0.01 * model.characteristic_length;
  // Scene points (SI): joint origins and output points per body, ground's too.
  std::vector<std::vector<Vec3>> pts(model.num_bodies());
  std::vector<Vec3> ground;
  for (const Joint& j : model.joints) {
    (j.body1 == kGround ? ground : pts[j.body1]).push_back(j.frame1.origin);
    (j.body2 == kGround ? ground : pts[j.body2]).push_back(j.frame2.origin);
  }
  for (const Output& o : model.outputs)
    if (o.kind == OutputKind::Point) pts[o.body1].push_back(o.point1);
  json scene_nodes = json::array();
  doc["nodes"].push_back({{"name", "ground"}});
  if (!ground.empty()) doc["nodes"][0]["mesh"] = AddMesh(BodyMesh(ground, w), AddMaterial(-1, &doc), &buf, &doc);
  scene_nodes.push_back(0);
  for (int b = 0; b < model.num_bodies(); ++b) {
    if (pts[b].empty()) pts[b].push_back(Vec3::Zero());
    doc["nodes"].push_back({{"name", model.bodies[b].name}, {"mesh", AddMesh(BodyMesh(pts[b], w), AddMaterial(b, &doc), &buf, &doc)}});
    scene_nodes.push_back(b + 1);
  }
  doc["scenes"] = {{{"nodes", scene_nodes}}};
  if (motion.rows() > 0) AddAnimation(model, motion, &buf, &doc);
  while (buf.bytes().size() % 4) buf.bytes().push_back(0);
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  json b = {{"byteLength", buf.bytes().size()}};
  if (!binary) b["uri"] = "data:application/octet-stream;base64," + Base64(buf.bytes());
  doc["buffers"] = {b};
  std::string out;
  if (binary) {
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    Put32(&out, 0x46546C67);  // "glTF"
    Put32(&out, 2);
    Put32(&out, static_cast<uint32_t>(12 + 8 + text.size() + 8 + buf.bytes().size()));
    Put32(&out, static_cast<uint32_t>(text.size()));
    Put32(&out, 0x4E4F534A);  // "JSON"
    out += text;
    Put32(&out, static_cast<uint32_t>(buf.bytes().size()));
    Put32(&out, 0x004E4942);  // "BIN\0"
    out.append(reinterpret_cast<const char*>(buf.bytes().data()), buf.bytes().size());
  } else {
    out = doc.dump(1) + "\n";
  }
  file->Write(out);
  return file->Commit("", error);
}

}  // namespace mechkin
