// Which files of an output directory grainlab wrote. Every result file is recorded, as its path
// relative to the directory, in DIR/.grainlab-outputs the moment it is first written; `--overwrite`
// removes exactly those (with their .tmp / .partial siblings, and their directories once empty)
// and nothing else, so a user's own files in the directory (a ParaView state in vtk/, notes) are
// never touched. A user's file that has the name of a result grainlab is about to write is not
// overwritten either: the run is refused, naming it.
#pragma once

#include <string>

namespace grainlab {

inline constexpr const char* manifest_name = ".grainlab-outputs";

// Creates DIR for a new run (ConfigError for a non-empty DIR unless `overwrite`, then the files
// of the manifest are removed) and makes it the directory whose outputs are recorded.
void prepare_output_dir(const std::string& dir, bool overwrite);

// Makes an existing DIR the recorded one without removing anything (resuming a run there).
void continue_in_output_dir(const std::string& dir);

// Records `path` (a file, or a directory ending in '/') if it lies in the current output
// directory; called by every writer of result files before it writes.
void record_output(const std::string& path);

}  // namespace grainlab
