#pragma once
// Whole-or-nothing output: write to a temporary file beside the target, then rename over it.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>

namespace corofem {

/// Calls write(stream) on a temporary file in the target's folder and renames it to `path` only if
/// writing succeeded. Throws InputError naming `path` if it cannot be written; no partial file is
/// left behind in either case.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Installs SIGINT/SIGTERM handlers that delete the temporary files being written, then end the
/// process as the signal would: an interrupted run leaves its earlier, complete outputs and no
/// partial file. Call once from main().
void remove_partial_outputs_on_interrupt();

/// Throws InputError if a file cannot be created in the folder of `path` (checked before long runs,
/// so an unwritable output is reported before the work, not after).
void check_writable(const std::filesystem::path& path);
/// Creates the output folder `dir` (with its parents) and checks that `file` can be written in
/// it; InputError naming the folder otherwise.
void prepare_output_folder(const std::filesystem::path& dir, const std::string& file);

}  // namespace corofem
