#pragma once
// The cost callgrind's output gives to calls into the C library's allocator (glibc's malloc.c,
// arena.c, morecore.c: the files under malloc/). What malloc and free do on a call follows the
// heap's whole history (its free lists, when it consolidates them), so an allocation added in one
// place moves the allocator's work between phases elsewhere: on the twisting bar, up to 2.6% of
// the coarsest update's instructions between two builds whose only change was an observer's
// allocations. The counted gate leaves the allocator out of the phases' counts.
#include <map>
#include <string>
#include <string_view>

#include "core/work_counts.hpp"

namespace corofem {

/// Reads callgrind's output line by line and sums, for the part being read, the inclusive cost of
/// every call from code outside the allocator into it (the allocator's own calls into itself, and
/// what it calls, sbrk and mmap, are inside that cost). Needs the C library's debug information
/// (Debian's libc6-dbg) for the file names; without it, seen() stays false.
class AllocatorCalls {
 public:
  /// Follows one line (of any kind) of callgrind's output, in order.
  void read(const std::string& line);
  /// The allocator's cost in the part read since the last take(), and starts the next part.
  WorkCounts take();
  /// Whether any of the allocator's functions appeared in the output.
  bool seen() const { return seen_; }

 private:
  /// A file (fl=, fi=, fe=, cfi=, cfl=) or function (fn=, cfn=) reference, "(id) name" or
  /// "(id)" with callgrind's name compression, or the bare name: whether it is the allocator's,
  /// `inherit` being the answer for a function first named here.
  bool file_is_allocator(std::string_view rest);
  bool function_is_allocator(std::string_view rest, bool inherit);
  void add_call_cost(const std::string& line);

  std::map<std::string, bool, std::less<>> files_, functions_;  ///< by compressed id
  bool in_allocator_file_ = false;                              ///< the current fl=
  bool in_allocator_ = false;                                   ///< the current fn=
  int callee_file_ = -1;  ///< the cfi=/cfl= before the next cfn=: -1 none, 0, 1
  bool callee_is_allocator_ = false;
  bool call_cost_next_ = false;         ///< the line after calls=: the call's inclusive cost
  int positions_ = 1;                   ///< the columns before the events ("positions: line")
  std::map<std::string, int> columns_;  ///< "events:" names to their column
  WorkCounts part_{};
  bool seen_ = false;
};

}  // namespace corofem
