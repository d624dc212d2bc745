#pragma once
// Which path tracer the path-tracer tests run. ctest runs each of their executables twice:
// as is ("path-scalar", the one-path-at-a-time reference) and with
// TRAY_TEST_PATH_INTEGRATOR=path (the default path tracer, its wavefront driver;
// tests/CMakeLists.txt, prefix "wavefront."), so their closed forms, references and stability
// scenes check both drivers.
#include <cstdlib>
#include <string>

namespace tray::test {

inline std::string pathUnderTest() {
  const char* name = std::getenv("TRAY_TEST_PATH_INTEGRATOR");
  return name && *name ? name : "path-scalar";
}

/// `name`, with "path" standing for the path tracer under test (tests listing integrators).
inline std::string orPathUnderTest(const std::string& name) {
  return name == "path" ? pathUnderTest() : name;
}

}  // namespace tray::test
