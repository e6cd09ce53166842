#include "core/allocator_calls.hpp"

#include <sstream>
#include <vector>

namespace corofem {

namespace {

bool starts_with(const std::string& line, std::string_view prefix) {
  return line.compare(0, prefix.size(), prefix) == 0;
}

/// "(12) name" -> ("(12)", "name"); "(12)" -> ("(12)", ""); "name" -> ("", "name").
std::pair<std::string_view, std::string_view> split_reference(std::string_view rest) {
  if (rest.empty() || rest.front() != '(') return {{}, rest};
  const std::size_t close = rest.find(')');
  if (close == std::string_view::npos) return {{}, rest};
  std::string_view name = rest.substr(close + 1);
  while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
  return {rest.substr(0, close + 1), name};
}

}  // namespace

bool AllocatorCalls::file_is_allocator(std::string_view rest) {
  const auto [id, name] = split_reference(rest);
  const bool named = !name.empty();
  const bool allocator = named && name.find("/malloc/") != std::string_view::npos;
  if (id.empty()) return allocator;
  if (named) files_[std::string(id)] = allocator;
  const auto it = files_.find(id);
  return it != files_.end() && it->second;
}

bool AllocatorCalls::function_is_allocator(std::string_view rest, bool inherit) {
  const auto [id, name] = split_reference(rest);
  if (id.empty()) return inherit;
  const auto it = functions_.find(id);
  if (it != functions_.end()) return it->second;
  if (!name.empty()) functions_.emplace(std::string(id), inherit);
  seen_ = seen_ || inherit;
  return inherit;
}

void AllocatorCalls::add_call_cost(const std::string& line) {
  std::istringstream in(line);
  std::string token;
  for (int p = 0; p < positions_ && in >> token; ++p) {
  }
  std::vector<std::uint64_t> v;
  while (in >> token) v.push_back(std::stoull(token));
  const auto at = [&](const char* event) {
    const auto it = columns_.find(event);
    return it != columns_.end() && it->second < static_cast<int>(v.size()) ? v[it->second] : 0;
  };
  part_ += {at("Ir"), at("D1mr") + at("D1mw"), at("DLmr") + at("DLmw")};
}

void AllocatorCalls::read(const std::string& line) {
  if (call_cost_next_) {
    call_cost_next_ = false;
    if (!in_allocator_ && callee_is_allocator_) add_call_cost(line);
    return;
  }
  if (starts_with(line, "fl=")) {
    in_allocator_file_ = file_is_allocator(std::string_view(line).substr(3));
  } else if (starts_with(line, "fi=") || starts_with(line, "fe=")) {
    file_is_allocator(std::string_view(line).substr(3));  // inlined code: the function stays
  } else if (starts_with(line, "fn=")) {
    in_allocator_ = function_is_allocator(std::string_view(line).substr(3), in_allocator_file_);
  } else if (starts_with(line, "cfi=") || starts_with(line, "cfl=")) {
    callee_file_ = file_is_allocator(std::string_view(line).substr(4)) ? 1 : 0;
  } else if (starts_with(line, "cfn=")) {
    const bool file = callee_file_ >= 0 ? callee_file_ == 1 : in_allocator_file_;
    callee_is_allocator_ = function_is_allocator(std::string_view(line).substr(4), file);
    callee_file_ = -1;
  } else if (starts_with(line, "calls=")) {
    call_cost_next_ = true;
  } else if (starts_with(line, "positions:")) {
    std::istringstream in(line.substr(10));
    std::string name;
    positions_ = 0;
    while (in >> name) ++positions_;
  } else if (starts_with(line, "events:")) {
    std::istringstream in(line.substr(7));
    std::string name;
    columns_.clear();
    for (int i = 0; in >> name; ++i) columns_[name] = i;
  }
}

WorkCounts AllocatorCalls::take() {
  const WorkCounts part = part_;
  part_ = {};
  return part;
}

}  // namespace corofem
