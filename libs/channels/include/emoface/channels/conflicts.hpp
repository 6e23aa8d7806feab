#pragma once
// Conflicting muscles (thesis §4.3, Table 4.1): pairs of muscles that cannot contract together.
// The printed table lost its columns; the default table is the reconstruction described in
// docs/channels.md (it reproduces the per-row mark counts that survive), kept as editable data in
// data/channels/conflicts.json.
#include <cstddef>
#include <string>
#include <vector>

namespace emoface::channels {

struct ConflictPair {
  std::string a;          ///< a muscle name (Table 2.1) or a parameter name
  std::string b;          ///< ditto, != a
  std::string rationale;  ///< one line: why they conflict (FACS action units)
};

struct ConflictTable {
  std::vector<ConflictPair> pairs;

  /// Throws InvalidInput for unknown names, a self pair or a repeated pair.
  void validate() const;

  /// Expands the pairs to `parameters`: result[i] lists the indices j with parameters[i] and
  /// parameters[j] in conflict. A muscle pair conflicts on the same side (_l with _l, _r with _r);
  /// an unpaired muscle (funneler, pressor, masseter) conflicts with both sides.
  std::vector<std::vector<std::size_t>> expand(const std::vector<std::string>& parameters) const;
};

/// The reconstructed Table 4.1 (18 pairs; same content as data/channels/conflicts.json).
ConflictTable default_conflict_table();

}  // namespace emoface::channels
