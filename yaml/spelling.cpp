#include "yaml/spelling.h"

#include <algorithm>
#include <cctype>

namespace metrosync::rigfile {

namespace {

// Optimal string alignment distance (Levenshtein plus adjacent transpositions), case-blind.
std::size_t editDistance(const std::string& a0, const std::string& b0) {
  std::string a = a0, b = b0;
  for (char& ch : a) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (char& ch : b) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

// The closest candidate if it is close enough to be a typo (or a prefix of at least 3 letters).
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& cands) {
  std::optional<std::string> best;
  std::size_t best_d = 0;
  for (const std::string& c : cands) {
    const std::size_t allowed = 1 + std::max(word.size(), c.size()) / 4;
    const bool prefix = word.size() >= 3 && c.compare(0, word.size(), word) == 0;
    // the distance is at least the difference in length: a word far longer than any key (a
    // 100 kB --set, found by the fuzz targets) is no typo, and costs no n x m table
    const std::size_t longer = std::max(word.size(), c.size());
    if (longer - std::min(word.size(), c.size()) > allowed && !prefix) continue;
    std::size_t d = editDistance(word, c);
    if (d > allowed && !prefix) continue;
    if (prefix) d = std::min<std::size_t>(d, allowed);
    if (!best || d < best_d) best = c, best_d = d;
  }
  return best;
}

}  // namespace metrosync::rigfile
