// The report's sections as units: the built-ins each have a renderer unit for their record, and a
// section registered from outside lib/ reaches the CLI's flags and usage, the driver and, with a
// renderer unit of its own, REPORT.md, without a change elsewhere. Registration changes the
// process for good, so the user's section is registered in a child process (a death test's fork).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/entry_point.hpp"
#include "mesh/box_mesh.hpp"
#include "report/report_section.hpp"
#include "report/scene_catalogue.hpp"
#include "test_support.hpp"

namespace corofem {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::read_text;
using test::TempDir;

bool python_present() {
  return std::system("python3 -c 'import sys' >/dev/null 2>&1") == 0;
}

/// The renderer's units as `render_report.py --units` lists them.
json renderer_units() {
  TempDir dir;
  const std::string command = "python3 '" +
                              (test::source_dir() / "reports" / "render_report.py").string() +
                              "' --units > '" + (dir / "units.json").string() + "'";
  if (std::system(command.c_str()) != 0) return nullptr;
  return json::parse(read_text(dir / "units.json"));
}

TEST(ReportSections, EachBuiltInSectionHasARendererUnitAndEachUnitASection) {
  if (!python_present()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  const json units = renderer_units();
  ASSERT_TRUE(units.is_array()) << "render_report.py --units failed";
  // Spelled out, so that a section lost from the registry fails here.
  const std::vector<std::string> expected = {"tables", "speed-accuracy", "stability",
                                             "model-accuracy"};
  EXPECT_EQ(report_section_names(), expected);
  std::vector<std::string> section_files, unit_files;
  for (const std::string& name : report_section_names())
    section_files.push_back(report_section(name).file);
  for (const json& unit : units)
    if (unit.at("report_section").get<bool>())
      unit_files.push_back(unit.at("records").at(0).get<std::string>());
  std::sort(section_files.begin(), section_files.end());
  std::sort(unit_files.begin(), unit_files.end());
  EXPECT_EQ(section_files, unit_files);
}

/// Runs `corofem ARGS...` in this process (the user's executable is corofem plus registrations).
int corofem_main(std::vector<std::string> args) {
  args.insert(args.begin(), "corofem");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return cli::main(static_cast<int>(argv.size()), argv.data());
}

/// What the CLI prints on stdout while `run` runs.
template <class F>
std::string stdout_of(F&& run) {
  std::ostringstream captured;
  std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
  run();
  std::cout.rdbuf(old);
  return captured.str();
}

/// A user's section: the tet count of a box mesh the size the report's mode asks for.
ReportSectionTraits mesh_census_section() {
  return {"mesh-census", "mesh census", "mesh_census.json",
          "the tets of a box mesh at the mode's size\nsecond line of the usage",
          [](const ReportConfig& config, std::vector<ReportRecord>& beside) {
            const int cells = config.mode == ReportConfig::Mode::Smoke ? 2 : 8;
            const TetMesh mesh = make_box_mesh({1, 1, 1}, {cells, cells, cells});
            beside.push_back({"mesh_census_cells.json", "mesh census cells", {{"cells", cells}}});
            return json{{"tets", mesh.num_tets()}};
          }};
}

void register_and_report_a_section_of_ones_own() {
  register_report_section(mesh_census_section());
  // The usage lists its flag and its record, the usage's second line indented under the first.
  const std::string help = stdout_of([] { corofem_main({"report", "--help"}); });
  EXPECT_NE(help.find("| --model-accuracy-only | --mesh-census-only]"), std::string::npos) << help;
  EXPECT_NE(help.find("  mesh_census.json     the tets of a box mesh at the mode's size\n"
                      "                       second line of the usage\n"),
            std::string::npos)
      << help;
  // Its flag runs it alone; the driver adds what produced it and writes what it made beside it.
  TempDir dir;
  const fs::path out = dir / "report";
  ASSERT_EQ(corofem_main(
                {"report", "--smoke", "--mesh-census-only", "--no-render", "--out", out.string()}),
            0);
  EXPECT_FALSE(fs::exists(out / "tables.json")) << "--mesh-census-only ran another section";
  const json record = json::parse(read_text(out / "mesh_census.json"));
  EXPECT_EQ(record.at("producer"), "corofem report (mesh census)");
  EXPECT_EQ(record.at("parameters").at("mode"), "smoke");
  EXPECT_TRUE(record.at("context").contains("commit"));
  EXPECT_TRUE(record.contains("elapsed_s"));
  EXPECT_EQ(record.at("tets"), 6 * 2 * 2 * 2);  // a box of n^3 cells has 6 n^3 tets
  EXPECT_EQ(json::parse(read_text(out / "mesh_census_cells.json")).at("cells"), 2);
  // Refused: a taken name, another section's record, a name that is no flag, a record that is no
  // JSON file, no run.
  auto refused = [](ReportSectionTraits traits, const std::string& why) {
    try {
      register_report_section(std::move(traits));
      ADD_FAILURE() << "registered: " << why;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  ReportSectionTraits twin = mesh_census_section();
  twin.file = "other.json";
  refused(twin, "registered already");
  ReportSectionTraits same_file = mesh_census_section();
  same_file.name = "census";
  same_file.file = "tables.json";
  refused(same_file, "section 'tables' writes tables.json already");
  ReportSectionTraits capital = mesh_census_section();
  capital.name = "Mesh census";
  refused(capital, "lower case letters");
  ReportSectionTraits text = mesh_census_section();
  text.name = "text-census";
  text.file = "census.txt";
  refused(text, "ending in .json");
  ReportSectionTraits idle = mesh_census_section();
  idle.name = "idle";
  idle.file = "idle.json";
  idle.run = nullptr;
  refused(idle, "no run");
  std::exit(::testing::Test::HasFailure() ? 1 : 0);
}

TEST(ReportSections, TheUsageNamesEveryModelAndStabilitySceneOnlyTakes) {
  const std::string help = stdout_of([] { corofem_main({"report", "--help"}); });
  std::vector<std::string> names = stability_scene_ids(true), files = file_models(),
                           procedural = procedural_models();
  names.insert(names.end(), files.begin(), files.end());
  names.insert(names.end(), procedural.begin(), procedural.end());
  for (const std::string& name : names) {
    // Each whole: followed by a comma or the list's closing parenthesis.
    const bool named = help.find(" " + name + ",") != std::string::npos ||
                       help.find("(" + name + ",") != std::string::npos ||
                       help.find(" " + name + ")") != std::string::npos;
    EXPECT_TRUE(named) << name << " in\n" << help;
  }
  // The list is wrapped at 100 columns.
  const std::size_t from = help.find("  --only NAME"), to = help.find("  --NAME-only");
  ASSERT_LT(from, to);
  std::istringstream lines(help.substr(from, to - from));
  for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
}

TEST(ReportSectionRegistryDeathTest, ASectionOfOnesOwnHasItsFlagUsageAndRecord) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(register_and_report_a_section_of_ones_own(), ::testing::ExitedWithCode(0), "");
}

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

TEST(ReportSections, ARendererUnitOfOnesOwnDrawsItsRecordInItsPlace) {
  if (!python_present()) GTEST_SKIP() << "no python3 on PATH: the renderer cannot run";
  TempDir dir;
  const fs::path units = dir / "units", report = dir / "report";
  fs::create_directories(units);
  fs::create_directories(report);
  write(units / "mesh_census.py",
        "ORDER = 65\nRECORDS = ('mesh_census.json',)\nREPORT_SECTION = True\n\n"
        "def render(records, folder, md):\n"
        "    if records['mesh_census.json']:\n"
        "        md.append(f\"## Mesh census\\n\\n{records['mesh_census.json']['tets']} "
        "tets\\n\\n\")\n");
  write(report / "mesh_census.json",
        R"j({"producer": "corofem report (mesh census)", "tets": 48})j");
  write(report / "model_accuracy.json",
        R"j({"producer": "corofem report (model accuracy)", "skipped": "no ccx"})j");
  const std::string render = (test::source_dir() / "reports" / "render").string();
  const std::string command = "COROFEM_REPORT_SECTIONS='" + units.string() + "' '" + render +
                              "' '" + report.string() + "' 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::string md = read_text(report / "REPORT.md");
  const std::size_t census = md.find("## Mesh census\n\n48 tets\n"),
                    stability = md.find("## Stability where methods fail"),
                    model = md.find("## Model accuracy against CalculiX");
  ASSERT_NE(census, std::string::npos) << md;
  // ORDER 65: after the stability study's place (60, absent here), before model accuracy (70).
  EXPECT_EQ(stability, std::string::npos);
  ASSERT_NE(model, std::string::npos) << md;
  EXPECT_LT(census, model);
  // Its record alone is a report to draw; a module that is no unit is refused by name.
  fs::remove(report / "model_accuracy.json");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  write(units / "broken.py", "ORDER = 1\n");
  const std::string refused =
      command.substr(0, command.size() - std::string(" 2>/dev/null").size()) + " 2> '" +
      (dir / "err").string() + "'";
  EXPECT_NE(std::system(refused.c_str()), 0);
  EXPECT_NE(read_text(dir / "err").find("broken.py is not a unit"), std::string::npos)
      << read_text(dir / "err");
}

}  // namespace
}  // namespace corofem
