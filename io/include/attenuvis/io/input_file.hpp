// Input files read whole, with the checks every reader needs first: the path
// names a regular file (not /dev/zero, a FIFO or a directory, which would be
// read forever or not at all) no larger than the reader's stated limit.
#pragma once

#include <cstddef>
#include <string>

namespace attenuvis::io {

// Throws std::runtime_error "'PATH': WHY" when the file cannot be opened, is
// not a regular file, or holds more than `max_bytes` bytes.
std::string read_input_file(const std::string& path, std::size_t max_bytes);

// The same checks without reading (for readers that stream, like tinyobjloader).
void require_readable_input(const std::string& path, std::size_t max_bytes);

}  // namespace attenuvis::io
