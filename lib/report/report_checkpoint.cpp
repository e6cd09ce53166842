#include "report/report_checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace corofem {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path units_file(const fs::path& dir, const std::string& section) {
  return dir / (section + ".jsonl");
}

/// The units a section's file holds: every whole line. A line a kill cut short (no newline) is
/// cut off the file, so that the resumed run's lines follow whole ones.
std::map<std::string, json> read_units(const fs::path& file) {
  std::map<std::string, json> units;
  std::uintmax_t whole = 0;  // bytes up to the last newline
  {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      if (in.eof()) break;  // no newline: the kill cut the line short
      whole += line.size() + 1;
      const json entry = json::parse(line, nullptr, false);
      if (entry.is_object() && entry.contains("unit") && entry.contains("output"))
        units[entry["unit"].get<std::string>()] = entry["output"];
    }
  }
  if (fs::file_size(file) != whole) fs::resize_file(file, whole);
  return units;
}

/// The differences between the killed run's parameters and these, for the message.
std::string differences(const json& before, const json& now) {
  std::string out;
  for (const auto& [key, value] : now.items())
    if (!before.contains(key) || before[key] != value)
      out += (out.empty() ? "" : ", ") + key + " " +
             (before.contains(key) ? before[key].dump() : "(none)") + " then, " + value.dump() +
             " now";
  return out;
}

}  // namespace

ReportCheckpoint::ReportCheckpoint(fs::path out_dir, json parameters, bool resume)
    : dir_(std::move(out_dir) / ".resume"), parameters_(std::move(parameters)) {
  if (!resume) {
    std::error_code ec;
    fs::remove_all(dir_, ec);
    fs::create_directories(dir_);
    write_state();
    return;
  }
  std::ifstream in(dir_ / "run.json");
  const json state = json::parse(in, nullptr, false);
  if (!in.is_open() || !state.is_object())
    throw InputError("report --resume: " + dir_.parent_path().string() +
                     " has no report to resume (none began there, or it ran to its end)");
  if (state.value("parameters", json()) != parameters_)
    throw InputError("report --resume: the report in " + dir_.parent_path().string() +
                     " began with other options or another build (" +
                     differences(state.value("parameters", json::object()), parameters_) +
                     "): give the options it began with");
  for (const json& section : state.value("done", json::array()))
    done_.insert(section.get<std::string>());
  for (const auto& entry : fs::directory_iterator(dir_))
    if (entry.path().extension() == ".jsonl")
      kept_[entry.path().stem().string()] = read_units(entry.path());
}

ReportCheckpoint::~ReportCheckpoint() = default;

void ReportCheckpoint::write_state() const {
  const json state = {{"parameters", parameters_}, {"done", done_}};
  write_file_atomically(dir_ / "run.json", [&](std::ostream& o) { o << state.dump(1) << '\n'; });
}

void ReportCheckpoint::finish_section(const std::string& section) {
  const std::lock_guard<std::mutex> guard(lock_);
  done_.insert(section);
  write_state();
}

void ReportCheckpoint::finish() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

json ReportCheckpoint::unit(const std::string& section, const std::string& name,
                            const std::function<json()>& run, bool* kept) {
  {
    const std::lock_guard<std::mutex> guard(lock_);
    const auto s = kept_.find(section);
    if (s != kept_.end())
      if (const auto u = s->second.find(name); u != s->second.end()) {
        if (kept) *kept = true;
        return u->second;
      }
  }
  if (kept) *kept = false;
  json output = run();
  // One write of one whole line, appended: a kill leaves it whole or cut short, never mixed with
  // another unit's (units side by side append under the lock).
  const std::string line = json{{"unit", name}, {"output", output}}.dump() + "\n";
  const std::lock_guard<std::mutex> guard(lock_);
  const fs::path file = units_file(dir_, section);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError("cannot write " + file.string() + ": " + std::strerror(errno));
  std::size_t written = 0;
  while (written < line.size()) {
    const ssize_t n = ::write(fd, line.data() + written, line.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      throw InputError("cannot write " + file.string() + ": " + std::strerror(errno));
    }
    written += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return output;
}

json report_unit(const ReportConfig& config, const std::string& section, const std::string& name,
                 const std::function<json()>& run, const std::string& progress_prefix) {
  if (!config.checkpoint) return run();
  bool kept = false;
  json output = config.checkpoint->unit(section, name, run, &kept);
  if (kept && config.progress && !progress_prefix.empty())
    *config.progress << progress_prefix << ": kept from the interrupted run" << std::endl;
  return output;
}

}  // namespace corofem
