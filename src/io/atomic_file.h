// Every output goes through here: written to a temporary file beside the target, flushed to
// disk, then renamed over it. A killed or failed run leaves the old file or the new one, never a
// torn one.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace hm {

// Calls write(stream) on a temporary file in the target's folder, then renames it to path.
// Throws IoError naming the path when the folder is missing or not writable, or when writing
// fails; the temporary file is removed on any failure (including an exception from write).
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace hm
