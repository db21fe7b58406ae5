// Following the curves from cell to cell (Burns11 §2.4.1.2), seeded by the previous frame's
// cells (§2.4.1.3) and by gradient-descent probes (§2.4.1.4); brute force as the reference.
#include <algorithm>
#include <deque>
#include <optional>
#include <unordered_map>

#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

namespace {

glm::ivec3 across(glm::ivec3 cell, int face) {
  glm::ivec3 step(0);
  step[face / 2] = face % 2 ? 1 : -1;
  return cell + step;
}

struct Link {
  glm::ivec3 cell;
  CellSegment segment;
};

class Walker {
 public:
  // `expected`: about how many cells the walk will read (the previous frame's), so that its
  // tables grow once.
  Walker(const VolumeLineField& field, VolumeLineSet& out, std::size_t expected = 0)
      : field_(field), out_(out) {
    cache_.reserve(2 * expected);
    out_.segments.reserve(2 * expected);
    cells_.reserve(2 * expected);
  }

  // Brute force: every cell's segments, so that walking needs no further reads. Returns the
  // cells that hold some, in cell-index order (the same field gives the same polylines).
  std::vector<glm::ivec3> examineAll() {
    std::vector<glm::ivec3> holding;
    const glm::ivec3 n = field_.cells();
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x) {
          const glm::ivec3 c(x, y, z);
          auto segments = field_.segments(c);
          if (segments.empty()) continue;
          cache_.emplace(field_.cellIndex(c), std::move(segments));
          holding.push_back(c);
        }
    out_.cellsExamined += std::size_t(n.x) * n.y * n.z;
    complete_ = true;
    return holding;
  }

  // The cells that hold the segments walked: the next frame's seeds.
  std::vector<std::uint64_t> walkedCells() {
    std::sort(cells_.begin(), cells_.end());
    cells_.erase(std::unique(cells_.begin(), cells_.end()), cells_.end());
    return std::move(cells_);
  }

  const std::vector<CellSegment>& segmentsOf(glm::ivec3 cell) {
    static const std::vector<CellSegment> none;
    const std::uint64_t key = field_.cellIndex(cell);
    if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
    if (complete_) return none;
    ++out_.cellsExamined;
    auto segments = field_.segments(cell);
    return cache_.emplace(key, std::move(segments)).first->second;
  }

  // Walks the loop through every segment of `cell` not yet drawn.
  void walkFrom(glm::ivec3 cell) {
    for (const CellSegment& s : segmentsOf(cell))
      if (!out_.segments.count(s.entryId)) walk({cell, s});
  }

  void probe(glm::vec3 p, int iterations) {
    const glm::vec3 hi(field_.cells());
    for (int i = 0; i < iterations; ++i) {
      // Alternately towards f = 0 and g = 0 (§2.4.1.4), testing the cell reached each time.
      p = field_.walkTowardsZero(p, i % 2);
      ++out_.cellsExamined;
      if (!glm::all(glm::greaterThanEqual(p, glm::vec3(0.0f))) ||
          !glm::all(glm::lessThan(p, hi)))
        return;  // left the volume
      const glm::ivec3 cell(glm::floor(p));
      if (!segmentsOf(cell).empty()) {
        walkFrom(cell);
        return;
      }
    }
  }

 private:
  // The segment the curve continues in across l's exit face (forward) or entry face.
  std::optional<Link> neighbour(const Link& l, bool forward) {
    const glm::ivec3 c = across(l.cell, forward ? l.segment.exitFace : l.segment.entryFace);
    if (!field_.validCell(c)) return std::nullopt;
    for (const CellSegment& s : segmentsOf(c))
      if (forward ? s.entryId == l.segment.exitId : s.exitId == l.segment.entryId)
        return Link{c, s};
    return std::nullopt;
  }
  std::optional<Link> next(const Link& l) { return neighbour(l, true); }
  std::optional<Link> previous(const Link& l) { return neighbour(l, false); }

  void walk(const Link& seed) {
    std::deque<Link> chain{seed};
    out_.segments.insert(seed.segment.entryId);
    bool closed = false;
    for (auto l = next(seed); l; l = next(*l)) {
      if (l->segment.entryId == seed.segment.entryId) {
        closed = true;
        break;
      }
      if (!out_.segments.insert(l->segment.entryId).second) break;
      chain.push_back(*l);
    }
    if (!closed)
      for (auto l = previous(seed); l; l = previous(*l)) {
        if (!out_.segments.insert(l->segment.entryId).second) break;
        chain.push_front(*l);
      }
    emit(std::vector<Link>(chain.begin(), chain.end()), closed);
  }

  // Splits a chain into runs of one kind (segments that fail the suggestive test end a run).
  void emit(std::vector<Link> chain, bool closed) {
    std::vector<std::optional<VolumeLineKind>> kinds;
    kinds.reserve(chain.size());
    for (const Link& l : chain)
      kinds.push_back(l.segment.kind < 0 ? std::nullopt
                                         : std::optional(VolumeLineKind(l.segment.kind)));
    if (closed) {
      // Start a loop where its kind changes, so that no run is cut at an arbitrary seed.
      const auto change = std::find_if(kinds.begin() + 1, kinds.end(),
                                       [&](const auto& k) { return k != kinds.front(); });
      if (change != kinds.end()) {
        const auto at = change - kinds.begin();
        std::rotate(chain.begin(), chain.begin() + at, chain.end());
        std::rotate(kinds.begin(), kinds.begin() + at, kinds.end());
        closed = false;  // the last run ends at the first one's start
      }
    }
    for (std::size_t i = 0; i < chain.size();) {
      std::size_t j = i;
      while (j < chain.size() && kinds[j] == kinds[i]) ++j;
      if (kinds[i]) {
        VolumeLine line{*kinds[i], {field_.toWorld(chain[i].segment.entry)}, closed};
        for (std::size_t k = i; k < j; ++k) line.points.push_back(field_.toWorld(chain[k].segment.exit));
        if (closed) line.points.pop_back();  // the last exit is the first entry
        out_.lines.push_back(std::move(line));
      }
      i = j;
    }
    for (const Link& l : chain) cells_.push_back(field_.cellIndex(l.cell));
  }

 private:
  const VolumeLineField& field_;
  VolumeLineSet& out_;
  std::unordered_map<std::uint64_t, std::vector<CellSegment>> cache_;
  bool complete_ = false;
  std::vector<std::uint64_t> cells_;  // of the segments walked, with repeats
};

}  // namespace

void walkVolumeLines(const VolumeLineField& field, const std::vector<glm::ivec3>& seeds,
                     VolumeLineSet& into) {
  Walker walker(field, into);
  for (const glm::ivec3& c : seeds)
    if (field.validCell(c)) walker.walkFrom(c);
  into.cells = walker.walkedCells();
}

VolumeLineSet extractVolumeLinesBruteForce(const VolumeLineField& field) {
  VolumeLineSet set;
  Walker walker(field, set);
  for (const glm::ivec3& c : walker.examineAll()) walker.walkFrom(c);
  set.cells = walker.walkedCells();
  return set;
}

VolumeLineSet VolumeLineTracker::extract(const VolumeLineField& field,
                                         const VolumeLineSeeding& seeding) {
  VolumeLineSet set;
  if (glm::any(glm::lessThanEqual(field.cells(), glm::ivec3(0)))) return set;  // no cell
  const bool first = !ran_;
  ran_ = true;
  if (first && seeding.bruteForceFirstFrame) {
    set = extractVolumeLinesBruteForce(field);
    previous_ = set.cells;
    return set;
  }
  Walker walker(field, set, previous_.size());
  const std::uint64_t cellCount = field.cellIndex(field.cells() - 1) + 1;
  std::erase_if(previous_, [&](std::uint64_t c) { return c >= cellCount; });
  if (seeding.previousCells)
    for (std::uint64_t c : previous_) walker.walkFrom(field.cellAt(c));
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  if (!previous_.empty()) {
    std::uniform_int_distribution<std::size_t> pick(0, previous_.size() - 1);
    for (int i = 0; i < seeding.probesFromPrevious; ++i)
      walker.probe(glm::vec3(field.cellAt(previous_[pick(random_)])) + 0.5f,
                   seeding.probeIterations);
  }
  const glm::vec3 extent(field.cells());
  for (int i = 0; i < seeding.randomProbes; ++i)
    walker.probe(glm::vec3(unit(random_), unit(random_), unit(random_)) * extent,
                 seeding.probeIterations);
  set.cells = walker.walkedCells();
  previous_ = set.cells;
  return set;
}

}  // namespace cutaway
