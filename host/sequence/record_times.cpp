#include "sequence/record_times.h"

#include <algorithm>

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
  return !moves.lights && !record_beside_any(record, moves.parts) &&
         moved_record_change(record, moves.parts) <= tolerance_;
}

size_t RecordMoves::bring_to(KeptRecords& kept, const RecordTimes& times, double now) {
  // The records of each time, in one pass (a merged file holds a key frame's records together, not all key frames').
  std::map<double, std::vector<size_t>> made_at;
  for (size_t i = 0; i < kept.size(); ++i) made_at[times.of(kept.last_used()[i])].push_back(i);
  size_t marked = 0;
  for (const auto& [t, group] : made_at) {
    if (t == now) continue;
    const Moves& moves = between(t, now);
    marked += moves.lights ? kept.mark_all_moved(&group) : kept.mark_moved(moves.parts, tolerance_, &group);
  }
  return marked;
}

}  // namespace rcsplat
