// tray-merge: combines the parts of a farm render (tray-render --region / --sample-range) into
// the image one machine would have rendered. Exit codes: 0 ok, 1 error writing, 2 bad parts.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "cli/part_merge.h"
#include "core/error.h"
#include "io/image_output.h"
#include "io/library_threads.h"

int main(int argc, char** argv) {
  tray::stopIdleLibraryThreads();
  std::vector<std::string> parts;
  std::string output;
  CLI::App app{"tray-merge: combine region and sample-range parts of a TRay render"};
  app.set_version_flag("--version", std::string("tray-merge ") + TRAY_VERSION);
  app.add_option("parts", parts, "part EXRs written by tray-render --region / --sample-range")
      ->required();
  app.add_option("-o,--output", output, "the merged .exr")->required();
  // One line, in the form of every other error (CLI11 adds a second "Run with --help" line).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("tray-merge: error: ") + e.what() + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
    tray::checkMergeOutput(parts, output);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const tray::Error& e) {
    std::fprintf(stderr, "tray-merge: error: %s\n", e.what());
    return 2;
  }
  const char* phase = "reading the parts";  // for the out-of-memory message
  try {
    tray::ExrImage merged = tray::mergeParts(parts);
    phase = "writing the image";
    if (const size_t clamped = tray::writeImage(merged.film, output, merged.options))
      std::fprintf(stderr, "warning: %s\n", tray::halfClampWarning(output, clamped).c_str());
    return 0;
  } catch (const tray::Error& e) {
    std::fprintf(stderr, "tray-merge: error: %s\n", e.what());
    return e.kind() == tray::Error::Kind::kInput ? 2 : 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "tray-merge: error: out of memory while %s\n", phase);
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tray-merge: error: %s\n", e.what());
    return 1;
  }
}
