#include "core/sampler.h"

#include "core/error.h"

namespace tray {

const std::vector<std::string>& Sampler::names() {
  static const std::vector<std::string> kNames = {"independent", "sobol"};
  return kNames;
}

const OptionSpec& Sampler::option() {
  static const OptionSpec spec = choiceOption(
      "sampler", "sobol", names(),
      "random sequence: sobol is Owen-scrambled and stratified (less noise per sample); "
      "ignored by adaptive's lattice");
  return spec;
}

Sampler::Sequence Sampler::parse(const std::string& name) {
  if (name == "independent") return Sequence::kIndependent;
  if (name == "sobol") return Sequence::kSobol;
  throw Error("unknown sampler '" + name + "' (known: independent, sobol)");
}

}  // namespace tray
