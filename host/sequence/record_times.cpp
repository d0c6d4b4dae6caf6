#include "sequence/record_times.h"

#include <algorithm>
#include <set>

namespace rcsplat {

const RecordMoves::Moves& RecordMoves::between(double t0, double t1) {
  const auto found = moves_.find({t0, t1});
  if (found != moves_.end()) return found->second;
  Moves moves;
  for (size_t i = 0; i < animator_.moving().size(); ++i) {
    const SceneAnimator::Between b = animator_.between(scene_, i, t0, t1);
    if (!b.moved) continue;
    const Scene::Mover& mover = scene_.movers[animator_.moving()[i]];
    moves.lights = moves.lights || mover.light >= 0;
    if (mover.triangle_count)
      moves.parts.push_back({frame_.to_device(glm::vec3(b.lo)), frame_.to_device(glm::vec3(b.hi)),
                             float(b.displacement / frame_.scale)});
  }
  return moves_.emplace(std::pair{t0, t1}, std::move(moves)).first->second;
}

bool RecordMoves::holds(const CacheRecord& record, double t0, double t1) {
  if (t0 == t1) return true;
  const Moves& moves = between(t0, t1);
  if (moves.lights) return false;
  double change = 0.0;
  for (const SweptBox& part : moves.parts) {
    if (record_beside_move(record, part)) return false;
    change += moved_record_change(record, part);
  }
  return change <= tolerance_;
}

size_t RecordMoves::bring_to(KeptRecords& kept, const RecordTimes& times, double now) {
  std::set<double> made_at;
  for (const uint64_t tag : kept.last_used()) made_at.insert(times.of(tag));
  size_t marked = 0;
  std::vector<char> group(kept.size());
  for (const double t : made_at) {
    if (t == now) continue;
    for (size_t i = 0; i < kept.size(); ++i) group[i] = times.of(kept.last_used()[i]) == t;
    const Moves& moves = between(t, now);
    marked += moves.lights ? kept.mark_all_moved(&group) : kept.mark_moved(moves.parts, tolerance_, &group);
  }
  return marked;
}

}  // namespace rcsplat
