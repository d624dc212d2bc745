// An integrator defined only here, with an int and a float option (and a diagnostic flag),
// registered through registerIntegrator: its declarations alone put its options on the command
// line (help, parsing, validation), into the farm job signature and into the EXR metadata.
// Each test drives the same functions tray-render's main does (cli/option_cli.h, cli/farm.h).
#include <gtest/gtest.h>

#include <filesystem>

#include "cli/option_cli.h"
#include "core/error.h"
#include "integrators/registry.h"
#include "io/image_input.h"
#include "render/farm.h"
#include "render/option_metadata.h"
#include "tests/raster_function.h"
#include "tests/temp_dir.h"

namespace tray::test {
namespace {

/// Li = toy-gain x toy-bounces everywhere: the pixels show that the options reached it.
class ToyIntegrator final : public Integrator {
 public:
  explicit ToyIntegrator(const RenderContext& ctx)
      : Integrator(ctx),
        value_(ctx.settings.getFloat("toy-gain") * float(ctx.settings.getInt("toy-bounces"))) {}
  Color Li(const Ray&, Sampler&, RayStats&, PrimaryHit*) const override { return Color(value_); }

 private:
  float value_;
};

const std::vector<OptionSpec>& toyOptions() {
  static const std::vector<OptionSpec> specs = {
      intOption("toy-bounces", 3, 0, 10, "bounces of the toy"),
      floatOption("toy-gain", 1.0f, 0.0f, 100.0f, "gain of the toy"),
      diagnostic(flagOption("toy-verbose", "talk while rendering")),
  };
  return specs;
}

std::unique_ptr<Integrator> makeToy(const RenderContext& ctx) {
  return std::make_unique<ToyIntegrator>(declaring(ctx, toyOptions()));
}

/// Registers the toy once per test binary, before its first use (no static initialisation
/// order to depend on).
void registerToy() {
  static const bool once = [] {
    registerIntegrator({"toy", "a test integrator", makeToy, toyOptions(), ""});
    return true;
  }();
  (void)once;
}

/// The settings tray-render would have after parsing `args`.
RenderSettings parse(const std::string& args, std::string* help = nullptr) {
  registerToy();
  RenderSettings settings;
  CLI::App app{"toy"};
  addRenderOptions(app, settings);
  if (help) *help = app.help();
  app.parse(args, false);
  return settings;
}

const JobFrame kFrame{"scenes/toy.gltf", -1, -1, 8, 6, "embree", "", "", ""};

TEST(ToyIntegrator, OptionsAppearInTheHelpWithDefaultAndRange) {
  std::string help;
  parse("", &help);
  EXPECT_NE(help.find("--toy-bounces INT"), std::string::npos) << help;
  EXPECT_NE(help.find("toy: bounces of the toy (default 3; 0..10)"), std::string::npos) << help;
  EXPECT_NE(help.find("--toy-gain FLOAT"), std::string::npos) << help;
  EXPECT_NE(help.find("toy: gain of the toy (default 1; 0..100)"), std::string::npos) << help;
  EXPECT_NE(help.find("--toy-verbose"), std::string::npos) << help;
  // The registry's names are the choices of --integrator.
  EXPECT_NE(help.find("whitted, adaptive, path, path-scalar, path-wavefront, bdpt, sppm, toy"),
            std::string::npos)
      << help;
}

/// The message of the tray::Error that `f` throws ("" if none).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ToyIntegrator, BadValuesAreRejectedNamingTheOption) {
  EXPECT_EQ(errorOf([] { validateOptions(parse("--integrator toy --toy-bounces 11")); }),
            "--toy-bounces 11: expected 0..10");
  EXPECT_EQ(errorOf([] { validateOptions(parse("--integrator toy --toy-gain -1")); }),
            "--toy-gain -1: expected 0..100");
  EXPECT_EQ(errorOf([] { parse("--toy-gain lots"); }), "--toy-gain lots: expected a number");
  EXPECT_EQ(errorOf([] { parse("--toy-bounces 2.5"); }),
            "--toy-bounces 2.5: expected an integer");
  // Checked even when another integrator renders: a bad value is a mistake either way.
  EXPECT_EQ(errorOf([] { validateOptions(parse("--integrator whitted --toy-bounces 11")); }),
            "--toy-bounces 11: expected 0..10");
  EXPECT_EQ(errorOf([] { validateOptions(parse("--integrator toy --toy-bounces 10")); }), "");
  // The same checks when code builds the settings instead of the command line.
  RenderSettings s;
  s.set("integrator", "toy");
  s.set("toy-gain", 1000);
  RasterWorld world;
  EXPECT_EQ(errorOf([&] { makeIntegrator(world.context(s, 1, 1)); }),
            "--toy-gain 1000: expected 0..100");
  s.set("toy-gian", 1);
  EXPECT_EQ(errorOf([&] { validateOptions(s); }), "--toy-gain 1000: expected 0..100");
  s.set("toy-gain", 2);
  EXPECT_EQ(errorOf([&] { validateOptions(s); }), "unknown option --toy-gian");
  EXPECT_EQ(errorOf([&] { (void)s.getInt("toy-bouncse"); }), "unknown option --toy-bouncse");
}

TEST(ToyIntegrator, OptionsReachTheIntegratorWithTheirDefaults) {
  RasterWorld world;
  RayStats stats;
  auto defaults = makeIntegrator(world.context(parse("--integrator toy"), 1, 1));
  EXPECT_EQ(defaults->renderPixel(0, 0, stats).radiance.x, 3.0f);
  auto set = makeIntegrator(
      world.context(parse("--integrator toy --toy-bounces 2 --toy-gain 2.5"), 1, 1));
  EXPECT_EQ(set->renderPixel(0, 0, stats).radiance.x, 5.0f);
}

TEST(ToyIntegrator, PixelOptionsDecideTheJobSignature) {
  const std::string job = jobSignature(parse("--integrator toy --toy-gain 2.5"), kFrame);
  EXPECT_NE(job.find(" integrator=toy "), std::string::npos) << job;
  EXPECT_NE(job.find(" toy-bounces=3 "), std::string::npos) << job;  // defaults are in it too
  EXPECT_NE(job.find(" toy-gain=2.5 "), std::string::npos) << job;
  EXPECT_NE(jobSignature(parse("--integrator toy --toy-gain 2"), kFrame), job);
  EXPECT_NE(jobSignature(parse("--integrator toy --toy-gain 2.5 --toy-bounces 4"), kFrame), job);
  // An explicit default is the same render; a diagnostic and another integrator's option
  // change no pixel.
  EXPECT_EQ(jobSignature(parse("--integrator toy --toy-gain 2.5 --toy-bounces 3"), kFrame), job);
  EXPECT_EQ(jobSignature(parse("--integrator toy --toy-gain 2.5 --toy-verbose"), kFrame), job);
  EXPECT_EQ(jobSignature(parse("--integrator toy --toy-gain 2.5 --aa-depth 2"), kFrame), job);
  EXPECT_EQ(job.find("toy-verbose"), std::string::npos) << job;
  // The toy's options are not in other integrators' signatures.
  EXPECT_EQ(jobSignature(parse("--toy-gain 2.5"), kFrame).find("toy-"), std::string::npos);
  // A wrapper's signature holds its inner integrator's options.
  const std::string wrapped =
      jobSignature(parse("--integrator adaptive --inner toy --toy-gain 2.5"), kFrame);
  EXPECT_NE(wrapped.find(" aa-depth=4 "), std::string::npos) << wrapped;
  EXPECT_NE(wrapped.find(" toy-gain=2.5 "), std::string::npos) << wrapped;
}

TEST(ToyIntegrator, PixelOptionsLandInTheExrMetadata) {
  ImageOutputOptions out;
  addOptionMetadata(parse("--integrator toy --toy-gain 2.5 --spp 4 --seed 9 --toy-verbose"), out);
  const std::filesystem::path path = testDir() / "toy_metadata.exr";
  writeImage(Film(2, 2), path.string(), out);
  const ImageOutputOptions read = readExr(path.string()).options;
  EXPECT_EQ(metadataString(read, "tray:integrator"), "toy");
  EXPECT_EQ(metadataString(read, "tray:toyGain"), "2.5");
  EXPECT_EQ(metadataString(read, "tray:toyBounces"), "3");
  EXPECT_EQ(metadataString(read, "tray:seed"), "9");
  EXPECT_EQ(metadataString(read, "tray:pixelSampler"), "auto");
  EXPECT_EQ(metadataFloat(read, "tray:spp", 0), 4.0f);  // a float, as readers expect
  EXPECT_EQ(metadataString(read, "tray:toyVerbose", "absent"), "absent");
}

}  // namespace
}  // namespace tray::test
