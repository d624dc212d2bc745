// libFuzzer target for what a user types and what TRAY_* extensions say (docs/fuzzing.md). The
// first byte picks the mode:
//   even: the rest is a NUL-separated argument list, parsed by the same declared options as
//         tray-render's command line (cli/option_cli.h) and validated (integrators/registry.h),
//         then turned into the farm job signature and the EXR metadata;
//   odd:  the rest is JSON placed as the TRAY_shape extension of a node and as the
//         TRAY_environment extension of the scene in a fixed, valid glTF document, loaded.
// Either must succeed or be refused: CLI11's ParseError or tray::Error. A crash, sanitizer
// report, leak, hang or any other exception is a bug.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/option_cli.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/farm.h"
#include "render/option_metadata.h"

namespace {

void fuzzOptions(const char* text, size_t size) {
  std::vector<std::string> args{"tray-render"};
  std::string current;
  for (size_t i = 0; i < size; ++i) {
    if (text[i] == '\0') {
      args.push_back(current);
      current.clear();
    } else {
      current += text[i];
    }
  }
  if (!current.empty()) args.push_back(current);
  if (args.size() > 64) return;  // long lists add nothing CLI11 has not seen
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  // Built once: constructing ~100 CLI11 options took most of each execution, and the set does
  // not depend on the input. clear() resets CLI11's parse state, the assignment the values.
  static tray::RenderSettings settings;
  static CLI::App& app = [] () -> CLI::App& {
    static CLI::App built{"fuzz"};
    tray::addRenderOptions(built, settings);
    return built;
  }();
  settings = tray::RenderSettings{};
  app.clear();
  try {
    app.parse(int(argv.size()), argv.data());
    tray::validateOptions(settings);
    const tray::RenderSettings all = tray::withIntegratorOptions(settings);
    tray::jobSignature(all, {"scene.gltf", -1, -1, 64, 48, "embree", "", "", ""});
    tray::ImageOutputOptions out;
    tray::addOptionMetadata(all, out);
  } catch (const CLI::ParseError&) {
  } catch (const tray::Error&) {
  }
}

void fuzzExtensions(const char* text, size_t size) {
  const std::string json(text, size);
  const std::string doc =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["TRAY_shape","TRAY_environment"],)"
      R"("materials":[{}],"scenes":[{"nodes":[0],"extensions":{"TRAY_environment":)" +
      json + R"(}}],"nodes":[{"extensions":{"TRAY_shape":)" + json + R"(}}]})";
  try {
    tray::loadGltfFromMemory(reinterpret_cast<const unsigned char*>(doc.data()), doc.size(),
                             "fuzz-extensions");
  } catch (const tray::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const char* rest = reinterpret_cast<const char*>(data + 1);
  if (data[0] % 2 == 0)
    fuzzOptions(rest, size - 1);
  else
    fuzzExtensions(rest, size - 1);
  return 0;
}
