// Binary .msh (v4.1 and v2.2): the same mesh written as ASCII and as binary reads to the same bits
// and runs to the same bits; gmsh's own binary files read; every truncation and every corrupted
// header of a binary file is refused with an error naming the file, never a crash.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "cli/run_scene.hpp"
#include "core/errors.hpp"
#include "mesh/box_mesh.hpp"
#include "mesh/gmsh_mesh.hpp"
#include "scene/scene.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

using test::expect_mesh_refused;
using test::TempDir;
using test::write_text;

template <class T>
void put(std::string& s, T value) {
  s.append(reinterpret_cast<const char*>(&value), sizeof value);
}

/// ASCII numbers in the shortest form that reads back to the same double (17 significant digits).
std::string exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

/// `mesh` as a .msh file of `version` (4.1 or 2.2), one volume entity, tags kept.
std::string msh_file(const TetMesh& mesh, double version, bool binary) {
  const bool v41 = version == 4.1;
  std::string s =
      std::string("$MeshFormat\n") + (v41 ? "4.1" : "2.2") + (binary ? " 1 8\n" : " 0 8\n");
  if (binary) {
    put<std::int32_t>(s, 1);
    s += "\n";
  }
  s += "$EndMeshFormat\n";
  const auto [lo, hi] = bounding_box(mesh.rest);
  const std::size_t nv = mesh.rest.size(), nt = mesh.tets.size();
  const auto node_tag = [&](int v) { return static_cast<std::uint64_t>(mesh.node_tags[v]); };
  if (v41) {
    s += "$Entities\n";
    if (binary) {
      for (std::uint64_t c : {0, 0, 0, 1}) put(s, c);
      put<std::int32_t>(s, 1);
      for (double x : {lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()}) put(s, x);
      put<std::uint64_t>(s, 0);
      put<std::uint64_t>(s, 0);
      s += "\n";
    } else {
      s += "0 0 0 1\n1 " + exact(lo.x()) + " " + exact(lo.y()) + " " + exact(lo.z()) + " " +
           exact(hi.x()) + " " + exact(hi.y()) + " " + exact(hi.z()) + " 0 0\n";
    }
    s += "$EndEntities\n$Nodes\n";
    const std::uint64_t min_node = *std::min_element(mesh.node_tags.begin(), mesh.node_tags.end());
    const std::uint64_t max_node = *std::max_element(mesh.node_tags.begin(), mesh.node_tags.end());
    if (binary) {
      for (std::uint64_t c : {std::uint64_t{1}, std::uint64_t{nv}, min_node, max_node}) put(s, c);
      for (std::int32_t c : {3, 1, 0}) put(s, c);
      put<std::uint64_t>(s, nv);
      for (std::size_t v = 0; v < nv; ++v) put(s, node_tag(v));
      for (const Vec3& x : mesh.rest) put(s, x.x()), put(s, x.y()), put(s, x.z());
      s += "\n";
    } else {
      s += "1 " + std::to_string(nv) + " " + std::to_string(min_node) + " " +
           std::to_string(max_node) + "\n3 1 0 " + std::to_string(nv) + "\n";
      for (std::size_t v = 0; v < nv; ++v) s += std::to_string(node_tag(v)) + "\n";
      for (const Vec3& x : mesh.rest)
        s += exact(x.x()) + " " + exact(x.y()) + " " + exact(x.z()) + "\n";
    }
    s += "$EndNodes\n$Elements\n";
    const std::uint64_t min_elem =
        *std::min_element(mesh.element_tags.begin(), mesh.element_tags.end());
    const std::uint64_t max_elem =
        *std::max_element(mesh.element_tags.begin(), mesh.element_tags.end());
    if (binary) {
      for (std::uint64_t c : {std::uint64_t{1}, std::uint64_t{nt}, min_elem, max_elem}) put(s, c);
      for (std::int32_t c : {3, 1, 4}) put(s, c);
      put<std::uint64_t>(s, nt);
      for (std::size_t e = 0; e < nt; ++e) {
        put<std::uint64_t>(s, mesh.element_tags[e]);
        for (int a = 0; a < 4; ++a) put(s, node_tag(mesh.tets[e][a]));
      }
      s += "\n";
    } else {
      s += "1 " + std::to_string(nt) + " " + std::to_string(min_elem) + " " +
           std::to_string(max_elem) + "\n3 1 4 " + std::to_string(nt) + "\n";
      for (std::size_t e = 0; e < nt; ++e) {
        s += std::to_string(mesh.element_tags[e]);
        for (int a = 0; a < 4; ++a) s += " " + std::to_string(node_tag(mesh.tets[e][a]));
        s += "\n";
      }
    }
    return s + "$EndElements\n";
  }
  s += "$Nodes\n" + std::to_string(nv) + "\n";
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3& x = mesh.rest[v];
    if (binary) {
      put(s, static_cast<std::int32_t>(node_tag(v)));
      put(s, x.x()), put(s, x.y()), put(s, x.z());
    } else {
      s += std::to_string(node_tag(v)) + " " + exact(x.x()) + " " + exact(x.y()) + " " +
           exact(x.z()) + "\n";
    }
  }
  s += std::string(binary ? "\n" : "") + "$EndNodes\n$Elements\n" + std::to_string(nt) + "\n";
  if (binary)
    for (std::int32_t c : {4, static_cast<std::int32_t>(nt), 2}) put(s, c);
  for (std::size_t e = 0; e < nt; ++e) {
    if (binary) {
      for (std::int32_t c : {static_cast<std::int32_t>(mesh.element_tags[e]), 0, 1}) put(s, c);
      for (int a = 0; a < 4; ++a) put(s, static_cast<std::int32_t>(node_tag(mesh.tets[e][a])));
    } else {
      s += std::to_string(mesh.element_tags[e]) + " 4 2 0 1";
      for (int a = 0; a < 4; ++a) s += " " + std::to_string(node_tag(mesh.tets[e][a]));
      s += "\n";
    }
  }
  return s + std::string(binary ? "\n" : "") + "$EndElements\n";
}

/// A 4x2x2 bar with every interior vertex moved off the lattice (coordinates use all 53 bits) and
/// sparse tags, so that a reader that rounds a digit or renumbers shows.
TetMesh jittered_bar() {
  TetMesh mesh = make_box_mesh(Vec3(2, 0.5, 0.5), {4, 2, 2});
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    mesh.rest[v] += 0.03 * Vec3(std::sin(1.3 * v), std::cos(2.1 * v), std::sin(0.7 * v + 1));
    mesh.node_tags[v] = 3 * v + 5;
  }
  for (int e = 0; e < mesh.num_tets(); ++e) mesh.element_tags[e] = 2 * e + 11;
  return mesh;
}

void expect_same_bits(const TetMesh& a, const TetMesh& b, const std::string& what) {
  ASSERT_EQ(a.rest.size(), b.rest.size()) << what;
  EXPECT_EQ(std::memcmp(a.rest.data(), b.rest.data(), a.rest.size() * sizeof(Vec3)), 0) << what;
  EXPECT_EQ(a.tets, b.tets) << what;
  EXPECT_EQ(a.node_tags, b.node_tags) << what;
  EXPECT_EQ(a.element_tags, b.element_tags) << what;
}

TEST(BinaryMsh, AsciiAndBinaryOfTheSameMeshReadToTheSameBits) {
  TempDir dir;
  const TetMesh bar = jittered_bar();
  for (double version : {4.1, 2.2}) {
    const std::string v = version == 4.1 ? "41" : "22";
    write_text(dir / ("ascii" + v + ".msh"), msh_file(bar, version, false));
    write_text(dir / ("binary" + v + ".msh"), msh_file(bar, version, true));
    const TetMesh ascii = read_volume_mesh(dir / ("ascii" + v + ".msh"));
    const TetMesh binary = read_volume_mesh(dir / ("binary" + v + ".msh"));
    expect_same_bits(ascii, binary, "v" + v);
    expect_same_bits(bar, binary, "v" + v + " against the mesh written");
  }
}

TEST(BinaryMsh, AsciiAndBinaryOfTheSameMeshRunToTheSameBits) {
  TempDir dir;
  const TetMesh bar = jittered_bar();
  write_text(dir / "ascii.msh", msh_file(bar, 4.1, false));
  write_text(dir / "binary.msh", msh_file(bar, 4.1, true));
  nlohmann::json scene = {{"material", {{"young", 1e5}, {"poisson", 0.3}, {"density", 1000}}},
                          {"fixed", {{{"box", {{-1, -1, -1}, {0.05, 1, 1}}}}}},
                          {"gravity", {0, 0, -9.81}},
                          {"analysis", {{"type", "dynamic"}, {"steps", 3}, {"dt", 0.01}}}};
  std::vector<nlohmann::json> displacement;
  for (const char* file : {"ascii.msh", "binary.msh"}) {
    scene["mesh"] = {{"file", file}};
    const SceneRun run = run_scene(parse_scene(scene, dir.path(), "scene.json"));
    displacement.push_back(run.record["displacement"]);
  }
  ASSERT_FALSE(displacement[0].empty());
  EXPECT_GT(std::abs(displacement[0].back()[2].get<double>()), 0.0);  // the bar moved
  EXPECT_EQ(displacement[0], displacement[1]);  // nlohmann compares the doubles exactly
}

TEST(BinaryMsh, GmshWrittenBinaryFilesRead) {
  // gmsh meshes a box and writes it as binary 4.1 and 2.2 (and ASCII 4.1, whose coordinates gmsh
  // prints with 16 digits, so it agrees with the binary ones to 1 ulp-ish, 1e-15 of the size).
  TempDir dir;
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
    gmsh::model::occ::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.4);
    gmsh::model::mesh::generate(3);
    gmsh::model::addPhysicalGroup(3, {1}, 7);
    gmsh::model::setPhysicalName(3, 7, "body");
    for (double version : {4.1, 2.2})
      for (int binary : {0, 1}) {
        gmsh::option::setNumber("Mesh.MshFileVersion", version);
        gmsh::option::setNumber("Mesh.Binary", binary);
        gmsh::write(
            (dir / ((version == 4.1 ? "v41" : "v22") + std::string(binary ? "b" : "a") + ".msh"))
                .string());
      }
    gmsh::finalize();
  }
  const TetMesh b41 = read_volume_mesh(dir / "v41b.msh");
  const TetMesh b22 = read_volume_mesh(dir / "v22b.msh");
  const TetMesh a41 = read_volume_mesh(dir / "v41a.msh");
  EXPECT_GT(b41.num_tets(), 20);
  // gmsh numbers the elements of a 2.2 file anew (only those of physical groups are written).
  ASSERT_EQ(b41.rest.size(), b22.rest.size());
  EXPECT_EQ(std::memcmp(b41.rest.data(), b22.rest.data(), b41.rest.size() * sizeof(Vec3)), 0);
  EXPECT_EQ(b41.tets, b22.tets);
  ASSERT_EQ(a41.rest.size(), b41.rest.size());
  EXPECT_EQ(a41.tets, b41.tets);
  for (std::size_t v = 0; v < a41.rest.size(); ++v)
    EXPECT_LE((a41.rest[v] - b41.rest[v]).norm(), 1e-15);
}

/// Offset of the first byte after `marker` (which must occur) in `s`.
std::size_t after(const std::string& s, const std::string& marker) {
  const std::size_t at = s.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  return at + marker.size();
}

template <class T>
std::string patched(std::string s, std::size_t at, T value) {
  std::memcpy(s.data() + at, &value, sizeof value);
  return s;
}

TEST(BinaryMsh, CorruptedHeadersAreRefusedNamingTheFault) {
  TempDir dir;
  TetMesh two = make_box_mesh(Vec3(1, 1, 1), {1, 1, 1});
  const std::string v41 = msh_file(two, 4.1, true), v22 = msh_file(two, 2.2, true);
  const std::size_t nodes = after(v41, "$Nodes\n"), elements = after(v41, "$Elements\n");
  const std::size_t node_block = nodes + 32, element_block = elements + 32;
  struct Case {
    const char* name;
    std::string bytes;
    const char* fragment;
  };
  const std::uint64_t huge = 1ULL << 61;
  const Case cases[] = {
      {"big_endian", patched<std::int32_t>(v41, after(v41, " 1 8\n"), 1 << 24), "other byte order"},
      {"v40", std::string(v41).replace(12, 3, "4.0"), "binary version"},
      {"node_blocks", patched(v41, nodes, huge), "the block count declares"},
      {"node_total", patched(v41, nodes + 8, huge), "the item count declares"},
      {"node_total_short", patched<std::uint64_t>(v41, nodes + 8, 7), "blocks list more nodes"},
      {"node_range", patched<std::uint64_t>(v41, nodes + 24, 2'000'000'000ULL), "tag range"},
      {"node_block_size", patched(v41, node_block + 12, huge), "blocks list more nodes"},
      {"node_parametric", patched<std::int32_t>(v41, node_block + 8, 7), "parametric 7"},
      {"node_twice", patched<std::uint64_t>(v41, node_block + 20 + 8, 1), "defined twice"},
      {"element_type", patched<std::int32_t>(v41, element_block + 8, 99), "element type 99"},
      {"element_total", patched(v41, elements + 8, huge), "the item count declares"},
      {"element_node", patched<std::uint64_t>(v41, element_block + 20 + 8, 77),
       "refers to node 77"},
      {"entities", patched(v41, after(v41, "$Entities\n") + 24, huge), "dimension-3 count"},
      {"unknown_section",
       std::string(v41).insert(after(v41, "$EndEntities\n"), "$Periodic\n0\n$EndPeriodic\n"),
       "unexpected '$Periodic'"},
      {"garbage_after", v41 + "junk\n", "unexpected 'junk'"},
      {"end_marker", std::string(v41).replace(v41.find("$EndNodes"), 9, "$EndNodez"), "expected"},
      {"v22_count", std::string(v22).replace(after(v22, "$Nodes\n"), 1, "99999"),
       "the header declares"},
      {"v22_block", patched<std::int32_t>(v22, after(v22, "$Elements\n6\n") + 4, 1 << 30),
       "bad block header"},
      {"v22_node_ref", patched<std::int32_t>(v22, after(v22, "$Elements\n6\n") + 12 + 12, 77),
       "refers to node 77"},
  };
  for (const Case& c : cases) {
    const auto file = dir / (std::string(c.name) + ".msh");
    write_text(file, c.bytes);
    SCOPED_TRACE(c.name);
    expect_mesh_refused(file, c.fragment);
  }
}

TEST(BinaryMsh, EveryTruncationIsRefused) {
  // Cut after every byte: each prefix is refused with InputError (ASan watches for overreads).
  TempDir dir;
  const TetMesh one = make_box_mesh(Vec3(1, 1, 1), {1, 1, 1});
  for (double version : {4.1, 2.2}) {
    const std::string whole = msh_file(one, version, true);
    const auto file = dir / "cut.msh";
    for (std::size_t n = 1; n + 1 < whole.size(); ++n) {
      write_text(file, whole.substr(0, n));
      EXPECT_THROW(read_volume_mesh(file), InputError)
          << "v" << version << " cut at " << n << " of " << whole.size();
    }
    write_text(file, whole);
    EXPECT_EQ(read_volume_mesh(file).num_tets(), 6);
  }
}

}  // namespace
}  // namespace corofem
