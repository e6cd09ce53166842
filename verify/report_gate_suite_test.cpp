// ci/bench-gate's suite, bench/gate/*.json, is the report's Table 1 scenes as `corofem run`
// scenes: each file must equal what report/scene_catalogue builds for its model and size, so the
// gate measures what the report measures. A file that differs is shown its expected text, to be
// copied by hand: the test never writes what it checks.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "report/scene_catalogue.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

struct GateScene {
  const char* file;
  const char* model;
  SceneSize size;
};

// Table 1's default rows that run in seconds: the quadruped at the paper's bunny and horse sizes
// (11k and 34k tets, derived coarse meshes) and the two bars; 25 steps (5 of warm-up and 20
// measured, as Table 1), MG-PCG to 1e-4 (the report's default tolerance).
const GateScene kSuite[] = {{"quadruped_11k.json", "quadruped", SceneSize::S},
                            {"quadruped_34k.json", "quadruped", SceneSize::M},
                            {"cantilever_small.json", "cantilever", SceneSize::Small},
                            {"twisting_bar_small.json", "twisting-bar", SceneSize::Small}};

TEST(GateSuite, ScenesAreTheReportsTableOneScenes) {
  const std::filesystem::path dir = test::source_dir() / "bench" / "gate";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    files += entry.path().extension() == ".json";
  EXPECT_EQ(files, static_cast<int>(std::size(kSuite))) << "a scene in " << dir << " not listed";
  for (const GateScene& g : kSuite) {
    const nlohmann::json expected = table_scene(g.model, g.size, 25, 1e-4);
    ASSERT_TRUE(std::filesystem::exists(dir / g.file)) << dir / g.file;
    EXPECT_EQ(nlohmann::json::parse(test::read_text(dir / g.file)), expected)
        << g.file << " differs from table_scene(" << g.model << ", " << size_name(g.size)
        << "), which is:\n"
        << expected.dump(2);
  }
}

}  // namespace
}  // namespace corofem
