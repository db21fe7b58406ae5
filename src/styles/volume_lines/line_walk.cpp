// Following the curves from cell to cell (Burns11 §2.4.1.2), seeded by the previous frame's
// cells (§2.4.1.3) and by gradient-descent probes (§2.4.1.4); brute force as the reference.
#include <algorithm>
#include <optional>
#include <sstream>

#include "cutaway/core/error.hpp"
#include "cutaway/styles/volume_lines.hpp"

namespace cutaway {

namespace {

glm::ivec3 across(glm::ivec3 cell, int face) {
  glm::ivec3 step(0);
  step[face / 2] = face % 2 ? 1 : -1;
  return cell + step;
}

// The segments of the cells read so far, by cell index: open addressing over one pool, so
// that a walk costs no allocation per cell (a walk reads few cells, many times each).
class CellCache {
 public:
  struct Span {
    std::uint32_t first = 0;
    std::uint8_t count = 0;
  };

  explicit CellCache(std::size_t expected) {
    keys_.assign(primeAtLeast(std::max<std::size_t>(61, 2 * expected)), kEmpty);
    spans_.resize(keys_.size());
    pool_.reserve(expected);
    drawn_.reserve(expected);
  }

  const Span* find(std::uint64_t cell) const {
    const std::size_t i = slot(cell);
    return keys_[i] == cell ? &spans_[i] : nullptr;
  }

  Span insert(std::uint64_t cell, const CellSegments& segments) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const Span span{std::uint32_t(pool_.size()), std::uint8_t(segments.count)};
    pool_.insert(pool_.end(), segments.begin(), segments.end());
    drawn_.resize(pool_.size(), false);
    const std::size_t i = slot(cell);
    keys_[i] = cell, spans_[i] = span, ++size_;
    return span;
  }

  const CellSegment& segment(std::uint32_t i) const { return pool_[i]; }
  bool drawn(std::uint32_t i) const { return drawn_[i]; }
  void draw(std::uint32_t i) { drawn_[i] = true; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);

  // The key's slot, or the empty slot where it would go (linear probing). The cell index
  // modulo the table's size, a prime: a walk's next cell is a neighbour along i, j or k, whose
  // slot is near (in cache), and no lattice stride piles cells onto a few slots.
  std::size_t slot(std::uint64_t key) const {
    std::size_t i = std::size_t(key % keys_.size());
    while (keys_[i] != key && keys_[i] != kEmpty) i = i + 1 == keys_.size() ? 0 : i + 1;
    return i;
  }

  static std::size_t primeAtLeast(std::size_t n) {
    const auto prime = [](std::size_t p) {
      for (std::size_t d = 3; d * d <= p; d += 2)
        if (p % d == 0) return false;
      return true;
    };
    n |= 1;
    while (!prime(n)) n += 2;
    return n;
  }

  void grow() {
    std::vector<std::uint64_t> keys(primeAtLeast(2 * keys_.size()), kEmpty);
    std::vector<Span> spans(keys.size());
    keys.swap(keys_), spans.swap(spans_);
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) {
        const std::size_t j = slot(keys[i]);
        keys_[j] = keys[i], spans_[j] = spans[i];
      }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<Span> spans_;
  std::size_t size_ = 0;
  std::vector<CellSegment> pool_;
  std::vector<bool> drawn_;
};

struct Link {
  glm::ivec3 cell;
  std::uint32_t segment;  // in the cache's pool
};

class Walker {
 public:
  // `expected`: about how many cells the walk will read (the previous frame's), so that its
  // tables grow once.
  Walker(const VolumeLineField& field, VolumeLineSet& out, std::size_t expected = 0)
      : field_(field), out_(out), cache_(expected) {
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
          const CellSegments segments = field_.segments(c);
          if (segments.empty()) continue;
          insert(field_.cellIndex(c), segments);
          holding.push_back(c);
        }
    out_.cellsExamined += std::size_t(n.x) * n.y * n.z;
    complete_ = true;
    return holding;
  }

  // Sorts the segments found and keeps the cells that hold them (the next frame's seeds).
  void finish() {
    std::sort(out_.segments.begin(), out_.segments.end());
    std::sort(cells_.begin(), cells_.end());
    cells_.erase(std::unique(cells_.begin(), cells_.end()), cells_.end());
    out_.cells = std::move(cells_);
  }

  CellCache::Span segmentsOf(glm::ivec3 cell) {
    const std::uint64_t key = field_.cellIndex(cell);
    if (const CellCache::Span* span = cache_.find(key)) return *span;
    if (complete_) return {};
    ++out_.cellsExamined;
    return insert(key, field_.segments(cell));
  }

  // Walks the loop through every segment of `cell` not yet drawn.
  void walkFrom(glm::ivec3 cell) {
    const CellCache::Span span = segmentsOf(cell);
    for (std::uint32_t i = span.first; i < span.first + span.count; ++i)
      if (!cache_.drawn(i)) walk({cell, i});
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
      if (segmentsOf(cell).count > 0) {
        walkFrom(cell);
        return;
      }
    }
  }

 private:
  // Caches a cell's segments, within the query's budget.
  CellCache::Span insert(std::uint64_t cell, const CellSegments& segments) {
    const CellCache::Span span = cache_.insert(cell, segments);
    if (span.first + span.count > field_.query().mostSegments) {
      std::ostringstream reason;
      reason << "the lines at isovalue " << field_.query().isoValue << " hold more than "
             << field_.query().mostSegments << " segments (noise-like data?)";
      throw Error(reason.str());
    }
    return span;
  }

  // The segment the curve continues in across l's exit face (forward) or entry face.
  std::optional<Link> neighbour(const Link& l, bool forward) {
    const CellSegment& from = cache_.segment(l.segment);
    const glm::ivec3 c = across(l.cell, forward ? from.exitFace : from.entryFace);
    if (!field_.validCell(c)) return std::nullopt;
    const std::uint64_t id = forward ? from.exitId : from.entryId;
    const CellCache::Span span = segmentsOf(c);
    for (std::uint32_t i = span.first; i < span.first + span.count; ++i)
      if ((forward ? cache_.segment(i).entryId : cache_.segment(i).exitId) == id) return Link{c, i};
    return std::nullopt;
  }

  // Marks a segment drawn; false if it already was.
  bool draw(const Link& l) {
    if (cache_.drawn(l.segment)) return false;
    cache_.draw(l.segment);
    out_.segments.push_back(cache_.segment(l.segment).entryId);
    return true;
  }

  void walk(const Link& seed) {
    // The chain is the seed's predecessors (nearest first) reversed, then the seed onwards.
    backward_.clear(), chain_.assign(1, seed);
    draw(seed);
    bool closed = false;
    for (auto l = neighbour(seed, true); l; l = neighbour(*l, true)) {
      if (l->segment == seed.segment) {
        closed = true;
        break;
      }
      if (!draw(*l)) break;
      chain_.push_back(*l);
    }
    if (!closed)
      for (auto l = neighbour(seed, false); l; l = neighbour(*l, false)) {
        if (!draw(*l)) break;
        backward_.push_back(*l);
      }
    chain_.insert(chain_.begin(), backward_.rbegin(), backward_.rend());
    emit(closed);
  }

  // Splits the chain into runs of one kind (segments that fail the suggestive test end a run).
  void emit(bool closed) {
    std::vector<Link>& chain = chain_;
    const auto kind = [&](std::size_t i) { return cache_.segment(chain[i].segment).kind; };
    if (closed) {
      // Start a loop where its kind changes, so that no run is cut at an arbitrary seed.
      std::size_t at = 1;
      while (at < chain.size() && kind(at) == kind(0)) ++at;
      if (at < chain.size()) {
        std::rotate(chain.begin(), chain.begin() + std::ptrdiff_t(at), chain.end());
        closed = false;  // the last run ends at the first one's start
      }
    }
    for (std::size_t i = 0; i < chain.size();) {
      std::size_t j = i;
      while (j < chain.size() && kind(j) == kind(i)) ++j;
      if (kind(i) >= 0) {
        VolumeLine line{VolumeLineKind(kind(i)),
                        {field_.toWorld(cache_.segment(chain[i].segment).entry)},
                        closed};
        line.points.reserve(j - i + 1);
        for (std::size_t k = i; k < j; ++k)
          line.points.push_back(field_.toWorld(cache_.segment(chain[k].segment).exit));
        if (closed) line.points.pop_back();  // the last exit is the first entry
        out_.lines.push_back(std::move(line));
      }
      i = j;
    }
    for (const Link& l : chain) cells_.push_back(field_.cellIndex(l.cell));
  }

  const VolumeLineField& field_;
  VolumeLineSet& out_;
  CellCache cache_;
  bool complete_ = false;
  std::vector<std::uint64_t> cells_;  // of the segments walked, with repeats
  std::vector<Link> chain_, backward_;
};

}  // namespace

bool VolumeLineSet::contains(std::uint64_t segment) const {
  return std::binary_search(segments.begin(), segments.end(), segment);
}

std::size_t VolumeLineSet::countFoundIn(const VolumeLineSet& other) const {
  std::size_t common = 0;
  auto j = other.segments.begin();
  for (std::uint64_t s : segments) {
    j = std::lower_bound(j, other.segments.end(), s);
    if (j == other.segments.end()) break;
    common += *j == s;
  }
  return common;
}

void walkVolumeLines(const VolumeLineField& field, const std::vector<glm::ivec3>& seeds,
                     VolumeLineSet& into) {
  Walker walker(field, into);
  for (const glm::ivec3& c : seeds)
    if (field.validCell(c)) walker.walkFrom(c);
  walker.finish();
}

VolumeLineSet extractVolumeLinesBruteForce(const VolumeLineField& field) {
  VolumeLineSet set;
  Walker walker(field, set);
  for (const glm::ivec3& c : walker.examineAll()) walker.walkFrom(c);
  walker.finish();
  return set;
}

VolumeLineSet VolumeLineTracker::extract(const VolumeLineField& field,
                                         const VolumeLineSeeding& seeding) {
  VolumeLineSet set;
  if (glm::any(glm::lessThanEqual(field.cells(), glm::ivec3(0)))) return set;  // no cell
  // Set once a frame is extracted: a frame that failed (Error) leaves the next one first.
  const bool first = !ran_;
  if (first && seeding.bruteForceFirstFrame) {
    set = extractVolumeLinesBruteForce(field);
    previous_ = set.cells;
    ran_ = true;
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
  walker.finish();
  previous_ = set.cells;
  ran_ = true;
  return set;
}

}  // namespace cutaway
