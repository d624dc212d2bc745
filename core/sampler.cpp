#include "core/sampler.h"

#include "core/error.h"

namespace tray {

const std::vector<std::string>& Sampler::names() {
  static const std::vector<std::string> kNames = {"independent", "sobol"};
  return kNames;
}

Sampler::Sequence Sampler::parse(const std::string& name) {
  if (name == "independent") return Sequence::kIndependent;
  if (name == "sobol") return Sequence::kSobol;
  throw Error("unknown sampler '" + name + "' (known: independent, sobol)");
}

}  // namespace tray
