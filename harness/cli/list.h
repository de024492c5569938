#pragma once
// `lodbench list`: every scheme with its seed, topology and parameters. Columns are sized from the
// content (long scheme and parameter names do not break them) and numbers are plain shortest text.
#include <string>
#include <vector>

namespace lb {

class Scheme;

std::string schemeListing(const std::vector<const Scheme*>& schemes);

}  // namespace lb
