// Records made at other times than the frame (issue 62 item 5; docs/ALGORITHM.md section 16): a cache file of a moving
// scene holds records of the times they were made at (render/kept_records.h RecordTimes): a merged pre-pass each
// record its key frame's, a walkthrough's cache the frame it ended on. A process that reads them brings each from its
// time to its frame's by what the scene did in between: the same bound a move in a walkthrough adds up
// (moved_record_change, summed over the parts that moved, marked past the tolerance; beside a part it goes), and
// every record marked where a light moved. A frame then computes the marked ones again where they stand.
#pragma once
#include <map>
#include <utility>
#include <vector>

#include "render/kept_records.h"
#include "scene/scene.h"
#include "scene/scene_animator.h"
#include "scene/scene_frame.h"

namespace rcsplat {

class RecordMoves {
 public:
  // scene: as the loader placed it; frame: the device coordinates the records are in; tolerance: as
  // --moved-record-tolerance.
  RecordMoves(const Scene& scene, const SceneAnimator& animator, const SceneFrame& frame, double tolerance)
      : scene_(scene), animator_(animator), frame_(frame), tolerance_(tolerance) {}

  // What moved from t0 to t1 (device coordinates): each moving part's swept box, and whether a light moved.
  struct Moves {
    std::vector<SweptBox> parts;
    bool lights = false;
  };
  const Moves& between(double t0, double t1);
  // Whether a record made at t0 still holds at t1: no light moved and the parts' moves would not mark it.
  bool holds(const CacheRecord& record, double t0, double t1);
  // Brings kept records, whose times `times` gives, to `now`: each group of records of one time is marked by the
  // moves from that time (KeptRecords::mark_moved over that group alone). Returns the records marked.
  size_t bring_to(KeptRecords& kept, const RecordTimes& times, double now);

 private:
  const Scene& scene_;
  const SceneAnimator& animator_;
  SceneFrame frame_;
  double tolerance_;
  std::map<std::pair<double, double>, Moves> moves_;
};

}  // namespace rcsplat
