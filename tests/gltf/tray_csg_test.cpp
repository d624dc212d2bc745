#include "gltf/tray_csg.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "shapes/box.h"
#include "shapes/quadric.h"
#include "shapes/sphere.h"
#include "shapes/torus.h"
#include "tests/base64.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

/// Writes a glTF file holding `nodes` (a JSON array body) with scene roots `roots`, two
/// materials, and optionally a cube mesh (mesh 0, [-1, 1]^3, 8 shared corners) or the same
/// cube with one face missing. (Welding of per-face vertices: mesh_solid_test, Khronos Box.)
std::string writeGltf(const std::string& name, const std::string& nodes, const std::string& roots,
                      bool cube = false, bool open = false) {
  std::string meshes;
  if (cube) {
    // 8 corners, 12 triangles wound outward; indices inline via a data: URI.
    const float p[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const uint16_t idx[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                              2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
    std::string bytes(reinterpret_cast<const char*>(p), sizeof p);
    bytes.append(reinterpret_cast<const char*>(idx), open ? sizeof idx - 12 : sizeof idx);
    const std::string enc = test::base64(bytes);
    size_t nIdx = open ? 30 : 36;
    meshes =
        R"(,"meshes":[{"name":"cube","primitives":[{"attributes":{"POSITION":0},"indices":1,"material":1}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-1,-1,-1],"max":[1,1,1]},
 {"bufferView":1,"componentType":5123,"count":)" +
        std::to_string(nIdx) + R"(,"type":"SCALAR"}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":)" +
        std::to_string(nIdx * 2) + R"(}],
"buffers":[{"byteLength":)" +
        std::to_string(bytes.size()) + R"(,"uri":"data:application/octet-stream;base64,)" + enc +
        R"("}])";
  }
  std::string path = (test::testDir() / name).string();
  std::ofstream(path) << R"({"asset":{"version":"2.0"},"extensionsUsed":["TRAY_shape"],"scene":0,
"scenes":[{"nodes":[)" + roots +
                             R"(]}],
"materials":[{"name":"red"},{"name":"green"}],
"nodes":[)" + nodes + "]" + meshes +
                             "}";
  return path;
}

const Primitive& onlyShape(const Scene& s) {
  EXPECT_EQ(s.primitives.size(), 1u);
  return s.primitives.at(0);
}

Ray line(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

TEST(TrayCsg, LoadsABoxMinusASphereWithOperandTransformsAndMaterials) {
  Scene s = loadGltf(writeGltf("diff.gltf", R"(
 {"name":"holed","translation":[0,0,-5],"extensions":{"TRAY_shape":{"type":"csg","op":"difference","children":[1,2],"material":0}}},
 {"name":"block","scale":[2,1,1],"extensions":{"TRAY_shape":{"type":"box"}}},
 {"name":"hole","translation":[2,0,0],"extensions":{"TRAY_shape":{"type":"sphere","radius":0.5,"material":1}}})",
                               "0"));
  const Primitive& p = onlyShape(s);
  // Along +x at the block's height: enters the box at x = -2, then hits the hole's wall
  // (flipped normal, the hole's material) only on the far side; the hole bites x in [1.5, 2].
  Hit h;
  ASSERT_TRUE(s.intersectShape(0, line({-5, 0, -5}, {1, 0, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 3.0f);
  EXPECT_EQ(s.surface(line({-5, 0, -5}, {1, 0, 0}), h).material, 0);
  ASSERT_TRUE(s.intersectShape(0, line({5, 0, -5}, {-1, 0, 0}), h));  // into the hole's cut
  EXPECT_FLOAT_EQ(h.t, 3.5f);
  SurfacePoint sp = s.surface(line({5, 0, -5}, {-1, 0, 0}), h);
  EXPECT_EQ(sp.material, 1);
  EXPECT_GT(sp.ng.x, 0.99f);  // the cut faces +x, towards where the hole opens
  EXPECT_EQ(p.name, "holed");
}

TEST(TrayCsg, MeshOperandWeldsHardEdgesAndCarriesItsMaterial) {
  Scene s = loadGltf(writeGltf("mesh.gltf", R"(
 {"name":"cut","extensions":{"TRAY_shape":{"type":"csg","op":"difference","children":[1,2]}}},
 {"name":"ball","extensions":{"TRAY_shape":{"type":"sphere","radius":1.5,"material":0}}},
 {"name":"cube","mesh":0,"translation":[1,0,0]})",
                               "0", true));
  Hit h;
  Ray r = line({5, 0.2f, 0.1f}, {-1, 0, 0});
  ASSERT_TRUE(s.intersectShape(0, r, h));
  EXPECT_NEAR(h.t, 5.0f, 1e-5f);  // the cube's face at x = 0, from the cube's material
  EXPECT_EQ(s.surface(r, h).material, 1);
}

TEST(TrayCsg, SampleSceneLoads) {
  Scene s = loadGltf(std::string(TRAY_SOURCE_DIR) + "/scenes/csg.gltf");
  int csgNodes = 0;
  for (const Primitive& p : s.primitives)
    if (auto* c = dynamic_cast<const Csg*>(p.shape.get())) {
      ++csgNodes;
      EXPECT_TRUE(c->bounds().finite()) << p.name;
    }
  EXPECT_EQ(csgNodes, 5);  // lens, die, bowl, grooved block, cut ball; operands are not placed
}

std::string loadError(const std::string& file) {
  try {
    loadGltf(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TrayCsg, UnboundedPlacedNodeIsAnErrorButAnUnboundedOperandIsNot) {
  const std::string ball = R"({"name":"ball","extensions":{"TRAY_shape":{"type":"sphere"}}})";
  const std::string ground = R"({"name":"ground","extensions":{"TRAY_shape":{"type":"plane"}}})";
  std::string err = loadError(writeGltf(
      "island.gltf",
      R"({"name":"island","extensions":{"TRAY_shape":{"type":"csg","op":"union","children":[1,2]}}},)" +
          ball + "," + ground,
      "0"));
  EXPECT_NE(err.find("CSG node 'island' is unbounded (union with the unbounded child 'ground')"),
            std::string::npos)
      << err;
  // The same union clipped by a sphere: fine.
  Scene s = loadGltf(writeGltf(
      "clipped.gltf",
      R"({"name":"clipped","extensions":{"TRAY_shape":{"type":"csg","op":"intersection","children":[3,4]}}},)" +
          ball + "," + ground +
          R"(,{"name":"island","extensions":{"TRAY_shape":{"type":"csg","op":"union","children":[1,2]}}},
       {"name":"big","extensions":{"TRAY_shape":{"type":"sphere","radius":3}}})",
      "0"));
  EXPECT_TRUE(onlyShape(s).shape->bounds().finite());
}

TEST(TrayCsg, BadCsgIsReportedWithTheNode) {
  auto csgNode = [](const std::string& body) {
    return R"({"name":"c","extensions":{"TRAY_shape":{"type":"csg",)" + body + "}}}";
  };
  const std::string ball = R"(,{"name":"ball","extensions":{"TRAY_shape":{"type":"sphere"}}})";
  EXPECT_NE(loadError(writeGltf("op.gltf", csgNode(R"("op":"xor","children":[1])") + ball, "0"))
                .find("unknown CSG op 'xor'"),
            std::string::npos);
  EXPECT_NE(loadError(writeGltf("none.gltf", csgNode(R"("op":"union","children":[])") + ball, "0"))
                .find("needs 'children'"),
            std::string::npos);
  EXPECT_NE(
      loadError(writeGltf("range.gltf", csgNode(R"("op":"union","children":[7])") + ball, "0"))
          .find("is not a node index"),
      std::string::npos);
  EXPECT_NE(loadError(writeGltf("self.gltf", csgNode(R"("op":"union","children":[0])") + ball, "0"))
                .find("contains itself"),
            std::string::npos);
  EXPECT_NE(
      loadError(writeGltf("empty.gltf",
                          csgNode(R"("op":"union","children":[1])") + R"(,{"name":"nothing"})",
                          "0"))
          .find("neither a TRAY_shape nor a mesh"),
      std::string::npos);
  EXPECT_NE(
      loadError(writeGltf("typo.gltf",
                          csgNode(R"("op":"union","children":[1],"chlidren":[1])") + ball, "0"))
          .find("unknown key 'chlidren'"),
      std::string::npos);
  EXPECT_NE(
      loadError(writeGltf("open.gltf",
                          csgNode(R"("op":"union","children":[1])") + R"(,{"name":"lid","mesh":0})",
                          "0", true, true))
          .find("not closed"),
      std::string::npos);
}

TEST(TrayShapeTypes, TorusAndQuadricsLoadWithTheirParameters) {
  Scene s = loadGltf(writeGltf("quadrics.gltf", R"(
 {"name":"t","extensions":{"TRAY_shape":{"type":"torus","majorRadius":2,"minorRadius":0.5}}},
 {"name":"c","extensions":{"TRAY_shape":{"type":"cylinder","radius":0.5,"height":2,"capped":true}}},
 {"name":"k","extensions":{"TRAY_shape":{"type":"cone","radius":0.5,"height":2}}},
 {"name":"p","extensions":{"TRAY_shape":{"type":"paraboloid"}}},
 {"name":"h","extensions":{"TRAY_shape":{"type":"hyperboloid","waist":0.2}}},
 {"name":"d","extensions":{"TRAY_shape":{"type":"disk","radius":2,"innerRadius":1}}})",
                               "0,1,2,3,4,5"));
  ASSERT_EQ(s.primitives.size(), 6u);
  auto* t = dynamic_cast<const Torus*>(s.primitives[0].shape.get());
  ASSERT_TRUE(t);
  EXPECT_EQ(t->majorRadius(), 2.0f);
  EXPECT_EQ(t->minorRadius(), 0.5f);
  auto* c = dynamic_cast<const Quadric*>(s.primitives[1].shape.get());
  ASSERT_TRUE(c);
  EXPECT_EQ(c->kind(), Quadric::Kind::kCylinder);
  EXPECT_TRUE(c->capped());
  EXPECT_EQ(c->height(), 2.0f);
  auto* k = dynamic_cast<const Quadric*>(s.primitives[2].shape.get());
  ASSERT_TRUE(k);
  EXPECT_FALSE(k->capped());  // open by default, as pbrt's
  EXPECT_TRUE(dynamic_cast<const Disk*>(s.primitives[5].shape.get()));
}

TEST(TrayShapeTypes, BadParametersAndOpenOperandsAreErrorsNamingTheNode) {
  EXPECT_NE(
      loadError(
          writeGltf(
              "badtorus.gltf",
              R"({"name":"fat","extensions":{"TRAY_shape":{"type":"torus","majorRadius":0.2,"minorRadius":0.5}}})",
              "0"))
          .find("'majorRadius' > 'minorRadius'"),
      std::string::npos);
  EXPECT_NE(
      loadError(
          writeGltf("badwaist.gltf",
                    R"({"name":"hy","extensions":{"TRAY_shape":{"type":"hyperboloid","waist":2}}})",
                    "0"))
          .find("'waist'"),
      std::string::npos);
  const std::string err = loadError(writeGltf("openop.gltf", R"(
 {"name":"cut","extensions":{"TRAY_shape":{"type":"csg","op":"difference","children":[1,2]}}},
 {"name":"ring","extensions":{"TRAY_shape":{"type":"torus"}}},
 {"name":"tube","extensions":{"TRAY_shape":{"type":"cylinder"}}})",
                                              "0"));
  EXPECT_NE(err.find("'tube'"), std::string::npos) << err;
  EXPECT_NE(err.find("open surface"), std::string::npos) << err;
}

TEST(TrayShapeTypes, TorusSceneLoads) {
  Scene s = loadGltf(std::string(TRAY_SOURCE_DIR) + "/scenes/torus.gltf");
  int tori = 0, quadrics = 0, csg = 0;
  for (const Primitive& p : s.primitives) {
    tori += dynamic_cast<const Torus*>(p.shape.get()) != nullptr;
    quadrics += dynamic_cast<const Quadric*>(p.shape.get()) != nullptr;
    csg += dynamic_cast<const Csg*>(p.shape.get()) != nullptr;
  }
  EXPECT_EQ(tori, 2);  // the gold torus and the lamp ring; the cut torus is a CSG operand
  EXPECT_EQ(quadrics, 3);
  EXPECT_EQ(csg, 1);
}

}  // namespace
}  // namespace tray
