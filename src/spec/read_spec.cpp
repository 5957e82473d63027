#include "spec/json_reader.hpp"
#include "spec/reader.hpp"

namespace mechkin {

using spec_reader::json;
using spec_reader::JsonReader;

// Sections in the order the compile step reads them (parameters before units,
// everything else after both), so that the two diagnostic lists merge in file order.
SpecReadResult ReadMechanismSpec(const std::string& text, const std::string& source_name) {
  SpecReadResult result;
  JsonReader rd(&result.diagnostics);
  const size_t slash = source_name.rfind('/');
  rd.set_folder(slash == std::string::npos ? "" : source_name.substr(0, slash + 1));
  json doc;
  rd.diagnostics().SetPlace(Section::Parse);
  if (!spec_reader::ParseJson(text, rd, &doc)) return result;
  MechanismSpec spec;
  if (!spec_reader::ReadHeader(rd, doc, &spec)) return result;
  spec.source = source_name;
  spec_reader::ReadParameters(rd, doc, &spec);
  spec_reader::ReadUnits(rd, doc, &spec);
  spec_reader::ReadGround(rd, doc, &spec);
  using spec_reader::ReadArray;
  const bool by_markers = spec_reader::JointsUseMarkers(doc);
  ReadArray(rd, doc, "bodies", "body", Section::Bodies,
            [&](const json& e, const std::string& p) { spec_reader::ReadBody(rd, e, p, by_markers, &spec); });
  ReadArray(rd, doc, "joints", "joint", Section::Joints,
            [&](const json& e, const std::string& p) { spec_reader::ReadJoint(rd, e, p, &spec); });
  ReadArray(rd, doc, "couplers", "coupler", Section::Couplers,
            [&](const json& e, const std::string& p) { spec_reader::ReadCoupler(rd, e, p, &spec); });
  ReadArray(rd, doc, "drivers", "driver", Section::Drivers,
            [&](const json& e, const std::string& p) { spec_reader::ReadDriver(rd, e, p, &spec); });
  spec_reader::ReadAnalysis(rd, doc, &spec);
  ReadArray(rd, doc, "outputs", "output", Section::Outputs,
            [&](const json& e, const std::string& p) { spec_reader::ReadOutput(rd, e, p, &spec); });
  spec_reader::ReadExpect(rd, doc, &spec);
  spec_reader::ReadGravity(rd, doc, &spec);
  ReadArray(rd, doc, "loads", "load", Section::Loads,
            [&](const json& e, const std::string& p) { spec_reader::ReadLoad(rd, e, p, &spec); });
  spec_reader::ReadView(rd, doc, &spec);
  spec.valid = !result.diagnostics.has_errors();
  result.spec = std::move(spec);
  return result;
}

}  // namespace mechkin
