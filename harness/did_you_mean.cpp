#include "did_you_mean.h"

#include <algorithm>
#include <cctype>

namespace lb {

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const bool same =
          std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      const size_t next = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = row[j];
      row[j] = next;
    }
  }
  return row[b.size()];
}

std::string didYouMean(const std::string& given, const std::vector<std::string>& known) {
  // A third of the name: "sphre" -> sphere, "tri-size" -> tri_size, but "level" is not "fps".
  const size_t limit = std::max<size_t>(1, given.size() / 3);
  const std::string* best = nullptr;
  size_t bestDistance = limit + 1;
  for (auto& k : known) {
    const size_t d = editDistance(given, k);
    if (d < bestDistance) {
      bestDistance = d;
      best = &k;
    }
  }
  return best ? "; did you mean '" + *best + "'?" : "";
}

}  // namespace lb
