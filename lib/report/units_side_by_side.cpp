#include "report/units_side_by_side.hpp"

#include <exception>
#include <mutex>
#include <optional>
#include <vector>

#include "core/line_stream.hpp"
#include "core/threads.hpp"

namespace corofem {

void run_units_side_by_side(int count, int workers, std::ostream* out,
                            const std::function<void(int unit, std::ostream* progress)>& body) {
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(count));
  std::mutex line_lock;
  const ScopedThreadCount one_each(1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(workers)
  for (int started = 0; started < count; ++started) {
    const int k = count - 1 - started;
    std::optional<LineStream> lines;
    if (out) lines.emplace(*out, line_lock);
    try {
      body(k, lines ? &*lines : nullptr);
    } catch (...) {
      failed[static_cast<std::size_t>(k)] = std::current_exception();  // none may leave the loop
    }
  }
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
}

}  // namespace corofem
