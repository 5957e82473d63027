#include "analysis/load.hpp"

#include "analysis/assemble_model.hpp"

namespace mechkin {

LoadResult Assembled(LoadResult loaded) {
  if (!loaded.ok() || !loaded.model->assembly) return loaded;
  Diagnostic error;
  if (!AssembleModel(&*loaded.model, &error)) {
    loaded.errors.push_back(error);
    loaded.model.reset();
  }
  return loaded;
}

LoadResult LoadMechanismFile(const std::string& path, const ParameterOverrides& overrides) {
  return Assembled(LoadFileUnassembled(path, overrides));
}

LoadResult LoadMechanismText(const std::string& text, const std::string& source_name,
                             const ParameterOverrides& overrides) {
  return Assembled(LoadTextUnassembled(text, source_name, overrides));
}

LoadResult WithParameters(const Model& model, const ParameterOverrides& overrides) {
  return Assembled(WithParametersUnassembled(model, overrides));
}

LoadResult CompileMechanism(std::shared_ptr<const MechanismSpec> spec, const ParameterOverrides& overrides) {
  return Assembled(Compile(std::move(spec), overrides));
}

LoadResult CompileMechanism(const MechanismSpec& spec, const ParameterOverrides& overrides) {
  return Assembled(Compile(spec, overrides));
}

}  // namespace mechkin
