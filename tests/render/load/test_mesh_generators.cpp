// Tests of render/load/mesh_generators: triangle counts, closedness and outward orientation of
// every generator, volumes against the analytic ones, subdivision, the bunny stand-ins and the
// JSON entry point (defaults, unknown keys and generators, determinism).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "engine/scene/mesh_topology.h"
#include "experiments/source_paths.h"
#include "render/load/mesh_generators.h"

namespace dv {
namespace {

constexpr double kPi = std::numbers::pi;
const std::string kAssets = test::source_dir() + "/experiments/assets";

void expect_closed_outward(const TriangleMesh& mesh) {
  EXPECT_TRUE(is_closed(mesh)) << mesh.name << ": " << open_edges(mesh).size() << " open edges";
  EXPECT_GT(signed_volume(mesh), 0.0) << mesh.name;
}

TriangleMesh generate(const Json& spec) {
  JsonReader reader(spec, "test.json", "/mesh");
  return generate_mesh(reader, kAssets);
}

std::string generate_error(const Json& spec) {
  try {
    generate(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MeshGenerators, BoxHasTwelveTrianglesAndExactVolume) {
  const TriangleMesh box = make_box(dvec3(-1.0, -2.0, 0.5), dvec3(1.0, 0.0, 1.0));
  EXPECT_EQ(box.positions.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  expect_closed_outward(box);
  EXPECT_DOUBLE_EQ(signed_volume(box), 2.0 * 2.0 * 0.5);
  EXPECT_THROW(make_box(dvec3(0.0), dvec3(1.0, 0.0, 1.0)), InputError);
}

TEST(MeshGenerators, QuadIsOpenWithUpwardNormal) {
  const TriangleMesh quad = make_quad(2.0);
  ASSERT_EQ(quad.triangles.size(), 2u);
  EXPECT_EQ(open_edges(quad).size(), 4u);
  for (const u32vec3& t : quad.triangles) {
    const dvec3 n = glm::cross(quad.positions[t.y] - quad.positions[t.x],
                               quad.positions[t.z] - quad.positions[t.x]);
    EXPECT_GT(n.y, 0.0);
    EXPECT_DOUBLE_EQ(n.x, 0.0);
    EXPECT_DOUBLE_EQ(n.z, 0.0);
  }
  for (const dvec3& p : quad.positions) {
    EXPECT_EQ(p.y, 0.0);
    EXPECT_DOUBLE_EQ(std::abs(p.x), 1.0);
    EXPECT_DOUBLE_EQ(std::abs(p.z), 1.0);
  }
}

TEST(MeshGenerators, SubdividedQuadHitsThePapersCount) {
  const TriangleMesh quad = make_subdivided_quad(1.0, 11858);
  EXPECT_EQ(quad.triangles.size(), 11858u);
  EXPECT_EQ(quad.positions.size(), 78u * 78u);
  EXPECT_EQ(open_edges(quad).size(), 4u * 77u);
  double area = 0.0;
  for (const u32vec3& t : quad.triangles) {
    const dvec3 n = glm::cross(quad.positions[t.y] - quad.positions[t.x],
                               quad.positions[t.z] - quad.positions[t.x]);
    EXPECT_GT(n.y, 0.0);
    area += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(area, 1.0, 1e-12);
}

TEST(MeshGenerators, SubdividedQuadCountsAreEvenAndClose) {
  EXPECT_EQ(make_subdivided_quad(1.0, 2).triangles.size(), 2u);
  // 5 -> 3 cells; 1 x 3 is too thin, so 1 x 2 or 2 x 2 (equally close): the square one wins.
  EXPECT_EQ(make_subdivided_quad(1.0, 5).triangles.size(), 8u);
  EXPECT_EQ(make_subdivided_quad(1.0, 200).triangles.size(), 200u);    // 10 x 10
  EXPECT_EQ(make_subdivided_quad(1.0, 1000).triangles.size(), 1000u);  // 20 x 25
  const long long prime_half = make_subdivided_quad(1.0, 2 * 5923).triangles.size();
  EXPECT_LE(std::llabs(prime_half - 2 * 5923), 2);  // 5923 is prime: closest product instead
  EXPECT_THROW(make_subdivided_quad(1.0, 1), InputError);
}

TEST(MeshGenerators, IcosphereCountsAndVolumeConverge) {
  const double r = 1.5;
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  for (int s = 0; s <= 4; ++s) {
    const TriangleMesh sphere = make_icosphere(r, s);
    EXPECT_EQ(sphere.triangles.size(), size_t(20 * std::pow(4, s)));
    expect_closed_outward(sphere);
    for (const dvec3& p : sphere.positions) EXPECT_NEAR(glm::length(p), r, 1e-12);
    // An inscribed polyhedron: too small, by an error that shrinks like the squared edge
    // length (measured: 0.395, 0.127, 0.034, 0.0086, 0.0022).
    const double relative_error = (exact - signed_volume(sphere)) / exact;
    EXPECT_GT(relative_error, 0.0);
    EXPECT_LT(relative_error, 0.6 * std::pow(0.25, s)) << "subdivisions " << s;
  }
}

TEST(MeshGenerators, UvSphereCylinderTorusCounts) {
  const TriangleMesh uv = make_uv_sphere(1.0, 24, 12);
  EXPECT_EQ(uv.triangles.size(), 2u * 24u * 11u);
  EXPECT_EQ(uv.positions.size(), 2u + 24u * 11u);
  expect_closed_outward(uv);
  EXPECT_NEAR(signed_volume(make_uv_sphere(1.0, 256, 128)), 4.0 / 3.0 * kPi, 0.002);

  const TriangleMesh cylinder = make_cylinder(0.5, 2.0, 40);
  EXPECT_EQ(cylinder.triangles.size(), 4u * 40u);
  expect_closed_outward(cylinder);
  // A regular 40-gon prism: (n/2) r^2 sin(2 pi/n) * h.
  EXPECT_NEAR(signed_volume(cylinder), 20.0 * 0.25 * std::sin(2.0 * kPi / 40.0) * 2.0, 1e-12);

  const TriangleMesh torus = make_torus(1.0, 0.25, 64, 32);
  EXPECT_EQ(torus.triangles.size(), 2u * 64u * 32u);
  expect_closed_outward(torus);
  EXPECT_NEAR(signed_volume(torus), 2.0 * kPi * kPi * 1.0 * 0.25 * 0.25, 0.01);
  EXPECT_THROW(make_torus(0.2, 0.3, 8, 8), InputError);
}

TEST(MeshGenerators, CupIsAClosedHollowSolid) {
  CupShape shape;
  const TriangleMesh cup = make_cup(shape);
  EXPECT_EQ(cup.triangles.size(), size_t(4 * shape.segments * shape.profile_samples));
  expect_closed_outward(cup);
  // Its volume is far below that of the solid it encloses: the cup is hollow.
  const double solid = kPi * shape.radius * shape.radius * shape.height;
  EXPECT_LT(signed_volume(cup), 0.35 * solid);
  EXPECT_GT(signed_volume(cup), 0.05 * solid);
  for (const dvec3& p : cup.positions) {
    EXPECT_GE(p.y, 0.0);
    EXPECT_LE(p.y, shape.height);
  }
  shape.wall = 0.4;
  EXPECT_THROW(make_cup(shape), InputError);
}

TEST(MeshGenerators, MidpointSubdivisionQuadruplesAndKeepsShape) {
  const TriangleMesh box = make_box(dvec3(0.0), dvec3(1.0));
  const TriangleMesh fine = subdivide(box, SubdivisionScheme::midpoint, 2);
  EXPECT_EQ(fine.triangles.size(), 12u * 16u);
  expect_closed_outward(fine);
  EXPECT_NEAR(signed_volume(fine), 1.0, 1e-12);
  const TriangleMesh quad = subdivide(make_quad(1.0), SubdivisionScheme::midpoint, 1);
  EXPECT_EQ(quad.triangles.size(), 8u);
  EXPECT_EQ(open_edges(quad).size(), 8u);
}

TEST(MeshGenerators, LoopAndSqrt3KeepClosedness) {
  const TriangleMesh box = make_box(dvec3(-1.0), dvec3(1.0));
  const TriangleMesh loop = subdivide(box, SubdivisionScheme::loop, 2);
  EXPECT_EQ(loop.triangles.size(), 12u * 16u);
  expect_closed_outward(loop);
  EXPECT_LT(signed_volume(loop), 8.0);  // Loop shrinks the box towards its smooth limit
  const TriangleMesh sqrt3 = subdivide(box, SubdivisionScheme::sqrt3, 2);
  EXPECT_EQ(sqrt3.triangles.size(), 12u * 9u);
  expect_closed_outward(sqrt3);
}

TEST(MeshGenerators, SubdivideToCountStopsAtFirstCountAboveTarget) {
  const TriangleMesh box = make_box(dvec3(0.0), dvec3(1.0));
  EXPECT_EQ(subdivide_to_count(box, SubdivisionScheme::midpoint, 12).triangles.size(), 12u);
  EXPECT_EQ(subdivide_to_count(box, SubdivisionScheme::midpoint, 13).triangles.size(), 48u);
  EXPECT_EQ(subdivide_to_count(box, SubdivisionScheme::sqrt3, 100).triangles.size(), 108u);
  EXPECT_THROW(subdivide_to_count(box, SubdivisionScheme::loop, kMaxGeneratedTriangles + 1),
               InputError);
}

TEST(MeshGenerators, BunnyStandInCounts) {
  // The shipped scan is already closed, so the counts are exactly 3,674 * 4^n.
  const size_t expected[] = {3674, 14696, 58784, 235136};
  for (int n = 0; n <= 3; ++n) {
    const TriangleMesh bunny = make_bunny(kAssets, n);
    EXPECT_EQ(bunny.triangles.size(), expected[n]) << n << " iterations";
    if (n == 0 || n == 3) expect_closed_outward(bunny);
  }
}

TEST(MeshGenerators, JsonDefaultsAndParameters) {
  EXPECT_EQ(generate({{"generator", "box"}}).triangles.size(), 12u);
  EXPECT_NEAR(signed_volume(generate({{"generator", "box"}, {"size", 2.0}})), 8.0, 1e-12);
  EXPECT_EQ(generate({{"generator", "subdivided_quad"}}).triangles.size(), 11858u);
  EXPECT_EQ(generate({{"generator", "icosphere"}}).triangles.size(), 20u * 64u);
  EXPECT_EQ(generate({{"generator", "icosphere"}, {"subdivisions", 1}}).triangles.size(), 80u);
  EXPECT_EQ(generate({{"generator", "torus"}, {"segments", 5}, {"sides", 4}}).triangles.size(),
            40u);
  EXPECT_EQ(
      generate({{"generator", "cup"}, {"segments", 8}, {"profile_samples", 3}}).triangles.size(),
      96u);
  EXPECT_EQ(generate({{"generator", "bunny"}, {"subdivisions", 1}}).triangles.size(), 14696u);
  const TriangleMesh refined =
      generate({{"generator", "box"}, {"subdivide", {{"scheme", "loop"}, {"iterations", 1}}}});
  EXPECT_EQ(refined.triangles.size(), 48u);
  const TriangleMesh counted = generate(
      {{"generator", "box"}, {"subdivide", {{"scheme", "midpoint"}, {"target_triangles", 700}}}});
  EXPECT_EQ(counted.triangles.size(), 768u);
}

TEST(MeshGenerators, JsonErrorsNameTheProblem) {
  const std::string unknown_key = generate_error({{"generator", "box"}, {"radius", 1.0}});
  EXPECT_NE(unknown_key.find("'radius'"), std::string::npos) << unknown_key;
  EXPECT_NE(unknown_key.find("test.json"), std::string::npos) << unknown_key;

  const std::string unknown_generator = generate_error({{"generator", "teapot"}});
  EXPECT_NE(unknown_generator.find("teapot"), std::string::npos) << unknown_generator;
  for (const std::string& name : mesh_generator_names())
    EXPECT_NE(unknown_generator.find(name), std::string::npos) << name;

  const std::string bad_scheme = generate_error(
      {{"generator", "box"}, {"subdivide", {{"scheme", "catmull"}, {"iterations", 1}}}});
  EXPECT_NE(bad_scheme.find("/mesh/subdivide/scheme"), std::string::npos) << bad_scheme;
  const std::string both = generate_error(
      {{"generator", "box"},
       {"subdivide", {{"scheme", "loop"}, {"iterations", 1}, {"target_triangles", 9}}}});
  EXPECT_NE(both.find("exactly one"), std::string::npos) << both;
  const std::string bad_value = generate_error({{"generator", "icosphere"}, {"radius", -1.0}});
  EXPECT_NE(bad_value.find("'radius' must be positive"), std::string::npos) << bad_value;
  EXPECT_NE(bad_value.find("test.json: /mesh"), std::string::npos) << bad_value;
  const std::string too_big = generate_error({{"generator", "icosphere"}, {"subdivisions", 13}});
  EXPECT_NE(too_big.find("more than"), std::string::npos) << too_big;
  EXPECT_NE(generate_error({{"radius", 1.0}}).find("generator"), std::string::npos);
  EXPECT_NE(generate_error({{"generator", "box"}, {"size", -1.0}}).find("/mesh/size: must be"),
            std::string::npos);
  EXPECT_NE(
      generate_error({{"generator", "box"}, {"size", 1.0}, {"min", {0, 0, 0}}}).find("not both"),
      std::string::npos);
}

TEST(MeshGenerators, SameParametersGiveIdenticalMeshes) {
  for (const std::string& name : mesh_generator_names()) {
    const Json spec = {{"generator", name}, {"subdivide", {{"scheme", "loop"}, {"iterations", 1}}}};
    if (name == "bunny") continue;  // covered below without the slower loop step
    const TriangleMesh a = generate(spec), b = generate(spec);
    EXPECT_EQ(a.positions, b.positions) << name;
    EXPECT_EQ(a.triangles, b.triangles) << name;
    EXPECT_FALSE(a.triangles.empty()) << name;
  }
  const TriangleMesh a = make_bunny(kAssets, 1), b = make_bunny(kAssets, 1);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
}

}  // namespace
}  // namespace dv
