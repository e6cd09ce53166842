// A hierarchy sized by the scene (issue 70): without `levels`, the levels go down to the first
// with at most coarsest_vertex_limit vertices; `levels` stays the override, and a cap.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/solver_record.hpp"
#include "multigrid/hierarchy_builder.hpp"
#include "scene/coarse_meshes.hpp"
#include "scene/scene.hpp"
#include "scene/scene_problem.hpp"
#include "scene/solver_factory.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

MeshSpec box_spec(std::array<int, 3> cells) {
  MeshSpec s;
  s.box = Vec3(2, 0.5, 0.5);
  s.cells = cells;
  return s;
}

/// Each level's vertex count, the fine one first.
std::vector<int> level_vertices(const TetMesh& fine, const BuiltHierarchy& built) {
  std::vector<int> v{fine.num_vertices()};
  for (const Transfer& t : built.transfers) v.push_back(t.coarse);
  return v;
}

TEST(SizedHierarchy, TheLimitFollowsTheSquareRootOfFortyTimesTheFineVertices) {
  HierarchyParams p;
  p.coarsest_vertices = kCoarsestSizedByFine;
  // sqrt(40 x 2653) = 325.8 (the bare bunny), sqrt(40 x 15174) = 779.1 (the bare dragon).
  EXPECT_EQ(coarsest_vertex_limit(p, 2653), 326);
  EXPECT_EQ(coarsest_vertex_limit(p, 15174), 780);
  p.coarsest_vertices = 500;
  EXPECT_EQ(coarsest_vertex_limit(p, 15174), 500);  // a scene's own limit
  p.coarsest_vertices = 0;
  EXPECT_EQ(coarsest_vertex_limit(p, 15174), 0);  // levels as given
  p.coarsest_vertices = kCoarsestSizedByFine;
  EXPECT_EQ(to_json(p)["coarsest_vertices_rule"], "sqrt(40 x fine vertices)");  // the rule recorded
}

TEST(SizedHierarchy, LevelsStopAtTheFirstWithinTheLimitAndLevelsStayTheCap) {
  const MeshSpec spec = box_spec({48, 12, 12});
  const TetMesh fine = load_scene_mesh(spec);
  const std::vector<char> fixed(fine.num_vertices(), 0);
  for (const HierarchyKind kind : {HierarchyKind::Lattice, HierarchyKind::Meshes}) {
    HierarchyParams p;
    p.kind = kind;
    p.levels = kSizedHierarchyMaxLevels;
    p.coarsest_vertices = kCoarsestSizedByFine;
    const int limit = coarsest_vertex_limit(p, fine.num_vertices());
    const std::vector<TetMesh> coarse =
        kind == HierarchyKind::Meshes
            ? coarse_meshes(spec, p.levels, "box", fine.num_vertices(), 0, limit)
            : std::vector<TetMesh>{};
    const std::vector<int> v = level_vertices(fine, build_hierarchy(fine, fixed, p, coarse));
    SCOPED_TRACE(kHierarchyKinds.name(kind));
    ASSERT_GE(v.size(), 3u) << "a 8,281-vertex box against a limit of " << limit;
    for (std::size_t h = 0; h + 1 < v.size(); ++h) EXPECT_GT(v[h], limit) << "level " << h;
    EXPECT_LE(v.back(), limit);
    // The derived meshes stop with the level that meets the limit: none meshed below it.
    if (kind == HierarchyKind::Meshes) {
      EXPECT_EQ(coarse.size() + 1, v.size());
    }
    // `levels` caps it; without a limit it is exactly `levels`.
    p.levels = 2;
    EXPECT_EQ(build_hierarchy(fine, fixed, p, coarse).transfers.size(), 1u);
    p.levels = static_cast<int>(v.size()) + 1;
    p.coarsest_vertices = 0;
    const std::vector<TetMesh> all = kind == HierarchyKind::Meshes
                                         ? coarse_meshes(spec, p.levels, "box", fine.num_vertices())
                                         : std::vector<TetMesh>{};
    EXPECT_EQ(build_hierarchy(fine, fixed, p, all).transfers.size(), v.size());
  }
}

TEST(SizedHierarchy, ThereIsAlwaysOneCoarseLevel) {
  const TetMesh fine = load_scene_mesh(box_spec({8, 2, 2}));
  HierarchyParams p;
  p.levels = kSizedHierarchyMaxLevels;
  p.coarsest_vertices = 10 * fine.num_vertices();  // the fine level is already within it
  const BuiltHierarchy built = build_hierarchy(fine, std::vector<char>(fine.num_vertices(), 0), p);
  EXPECT_EQ(built.transfers.size(), 1u);
}

TEST(SizedHierarchy, AMeshFileGivesItsLevelsAndNoMore) {
  test::TempDir dir;
  // The given coarse level: a 4 x 1 x 1 box written as a gmsh 2.2 file (a file is not re-meshed).
  const TetMesh box = load_scene_mesh(box_spec({4, 1, 1}));
  std::ostringstream msh;
  msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << box.num_vertices() << "\n";
  for (int i = 0; i < box.num_vertices(); ++i)
    msh << i + 1 << " " << box.rest[i].x() << " " << box.rest[i].y() << " " << box.rest[i].z()
        << "\n";
  msh << "$EndNodes\n$Elements\n" << box.num_tets() << "\n";
  for (int e = 0; e < box.num_tets(); ++e)
    msh << e + 1 << " 4 2 0 1 " << box.tets[e][0] + 1 << " " << box.tets[e][1] + 1 << " "
        << box.tets[e][2] + 1 << " " << box.tets[e][3] + 1 << "\n";
  msh << "$EndElements\n";
  test::write_text(dir / "c.msh", msh.str());
  MeshSpec fine = box_spec({16, 4, 4});
  MeshSpec given;
  given.kind = MeshSpec::Kind::File;
  given.path = dir / "c.msh";
  fine.levels = {given};
  const int fine_vertices = load_scene_mesh(fine).num_vertices();
  // Sized (a limit below the file's 20 vertices): the file's level, then no more.
  EXPECT_EQ(coarse_meshes(fine, kSizedHierarchyMaxLevels, "s", fine_vertices, 0, 5).size(), 1u);
  // Three levels asked outright: the second cannot be made, and the message says why.
  try {
    coarse_meshes(fine, 3, "s", fine_vertices);
    ADD_FAILURE() << "a third level was made from a mesh file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be re-meshed"), std::string::npos) << e.what();
  }
}

nlohmann::json scene_with(const nlohmann::json& analysis) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "mesh": {"box": [1, 0.1, 0.1], "cells": [4, 1, 1]},
    "material": {"young": 1e6, "poisson": 0.3, "density": 1000},
    "fixed": [{"box": [[0, 0, 0], [0, 0.1, 0.1]]}]
  })");
  j["analysis"] = analysis;
  return j;
}

TEST(SizedHierarchy, AScenesLevelsAndLimitReachTheHierarchy) {
  const auto analysis = [](const nlohmann::json& a) {
    return parse_scene(scene_with(a), "/", "s.json").analysis;
  };
  const auto params = [&](const nlohmann::json& a) {
    return multigrid_params(analysis(a)).hierarchy;
  };
  HierarchyParams p = params({{"solver", "mgpcg"}});  // neither: sized by the scene
  EXPECT_EQ(p.levels, kSizedHierarchyMaxLevels);
  EXPECT_EQ(p.coarsest_vertices, kCoarsestSizedByFine);
  p = params({{"solver", "auto"}, {"type", "dynamic"}});
  EXPECT_EQ(p.coarsest_vertices, kCoarsestSizedByFine);
  p = params({{"solver", "mgpcg"}, {"levels", 3}});  // the override: exactly 3
  EXPECT_EQ(p.levels, 3);
  EXPECT_EQ(p.coarsest_vertices, 0);
  p = params({{"solver", "multigrid"}, {"coarsest_vertices", 900}});
  EXPECT_EQ(p.levels, kSizedHierarchyMaxLevels);
  EXPECT_EQ(p.coarsest_vertices, 900);
  p = params({{"solver", "mgpcg"}, {"levels", 4}, {"coarsest_vertices", 900}});  // 4 at most
  EXPECT_EQ(p.levels, 4);
  EXPECT_EQ(p.coarsest_vertices, 900);
  const AnalysisSpec direct = analysis({{"solver", "cholmod"}});
  EXPECT_EQ(direct.multigrid.hierarchy.levels, 1);
  EXPECT_EQ(direct.multigrid.hierarchy.coarsest_vertices, 0);
  try {
    analysis({{"solver", "mgpcg"}, {"coarsest_vertices", 0}});
    ADD_FAILURE() << "coarsest_vertices 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("analysis.coarsest_vertices must be in [1, 1000000]"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace corofem
