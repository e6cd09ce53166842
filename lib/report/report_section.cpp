// The registry behind report_section.hpp: the built-in sections, each from its own file, then
// whatever a user's program registers.
#include "report/report_section.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/named_registry.hpp"
#include "report/model_accuracy.hpp"
#include "report/paper_tables.hpp"
#include "report/speed_accuracy.hpp"
#include "report/stability_study.hpp"

namespace corofem {
namespace {

NamedRegistry<ReportSectionTraits>& registry() {
  static NamedRegistry<ReportSectionTraits> sections(
      {paper_tables_section(), speed_accuracy_section(), stability_section(),
       model_accuracy_section()},
      "report section");
  return sections;
}

bool is_flag_name(const std::string& name) {
  return !name.empty() && name.front() != '-' && name.back() != '-' &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
         });
}

}  // namespace

void register_report_section(ReportSectionTraits traits) {
  const std::string what = "register report section '" + traits.name + "': ";
  if (!traits.name.empty() && !is_flag_name(traits.name))
    throw std::invalid_argument(what +
                                "a name is lower case letters, digits and '-' (its flag is "
                                "--NAME-only)");
  if (traits.file.size() <= 5 || !traits.file.ends_with(".json") ||
      traits.file.find('/') != std::string::npos)
    throw std::invalid_argument(what + "its record is a file name ending in .json, not '" +
                                traits.file + "'");
  for (const std::string& name : registry().names())
    if (registry().at(registry().index_of(name)).file == traits.file)
      throw std::invalid_argument(what + "section '" + name + "' writes " + traits.file +
                                  " already");
  if (!traits.run) throw std::invalid_argument(what + "no run");
  if (traits.label.empty()) traits.label = traits.name;
  registry().add(std::move(traits));
}

std::vector<std::string> report_section_names() {
  return registry().names();
}

const ReportSectionTraits& report_section(std::string_view name) {
  return registry().at(registry().index_of(name));
}

}  // namespace corofem
