#pragma once
// A registry of named traits records (rotation methods, smoothers): the built-ins first, then what
// a user's program adds before it runs anything. Entries never move (a deque), so references and
// indices handed out stay valid; reading from any thread once registration is over.
#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace corofem {

template <class Traits>
class NamedRegistry {
 public:
  /// `what` names an entry in messages ("rotation method", "smoother").
  NamedRegistry(std::deque<Traits> built_in, std::string what)
      : entries_(std::move(built_in)), what_(std::move(what)) {}

  /// Adds an entry; its name must be non-empty and new. Returns its index.
  std::size_t add(Traits traits) {
    if (traits.name.empty()) throw std::invalid_argument("register " + what_ + ": no name");
    if (find(traits.name))
      throw std::invalid_argument("register " + what_ + ": '" + traits.name +
                                  "' is registered already");
    entries_.push_back(std::move(traits));
    return entries_.size() - 1;
  }
  std::optional<std::size_t> find(std::string_view name) const {
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (entries_[i].name == name) return i;
    return std::nullopt;
  }
  /// The index of `name`; std::out_of_range naming the registered entries for another.
  std::size_t index_of(std::string_view name) const {
    if (auto i = find(name)) return *i;
    std::string list;
    for (const std::string& n : names()) list += (list.empty() ? "" : ", ") + n;
    throw std::out_of_range("no " + what_ + " named '" + std::string(name) +
                            "' (registered: " + list + ")");
  }
  const Traits& at(std::size_t i) const { return entries_.at(i); }
  std::size_t size() const { return entries_.size(); }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const Traits& t : entries_) out.push_back(t.name);
    return out;
  }

 private:
  std::deque<Traits> entries_;
  std::string what_;
};

}  // namespace corofem
