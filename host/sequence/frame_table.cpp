#include "sequence/frame_table.h"

#include <sstream>

namespace rcsplat {

const char* const kFrameTableHeader =
    "frame,time_s,seconds,kernel_build_s,bvh_s,upload_s,probe_s,gbuffer_s,direct_s,photons_s,caustics_s,guide_s,"
    "records_s,placement_s,splat_s,radiance_s,resolve_s,glossy_s,path_s,layers_s,records,records_reused,"
    "records_added,records_evicted,radiance_records,radiance_reused,radiance_added,radiance_evicted,primary_rays,"
    "shadow_rays,record_rays,radiance_rays,glossy_rays,"
    "path_rays,device_peak_bytes,host_peak_bytes,records_moved,radiance_moved,records_ahead,windows,ahead_s\n";

std::string frame_table_row(const FrameRow& r) {
  const RenderStats& s = r.stats;
  std::ostringstream out;
  out.precision(6);
  out << r.frame << ',' << r.time << ',' << s.total_s << ',' << s.program_s;
  for (const RenderStats::StageTime& stage : s.stage_times()) out << ',' << stage.seconds;
  const KeptRecordsStats& k = s.kept_records;
  const bool kept = k.capacity > 0;  // else a cache per frame: every record is new, none is kept
  out << ',' << s.irradiance.records << ',' << k.reused << ',' << (kept ? k.added : s.irradiance.records) << ','
      << k.evicted << ',' << s.radiance.records << ',' << s.kept_radiance_records.reused << ','
      << (kept ? s.kept_radiance_records.added : s.radiance.records) << ',' << s.kept_radiance_records.evicted << ','
      << s.primary.primary_rays << ',' << s.primary.shadow_rays << ','
      << s.irradiance.rays << ',' << s.radiance.rays << ',' << s.glossy.rays << ',' << s.path.rays << ','
      << s.device_memory.peak_bytes << ',' << r.host_peak_bytes << ',' << k.moved << ','
      << s.kept_radiance_records.moved << ',' << k.ahead << ',' << k.windows << ',' << k.ahead_s << '\n';
  return out.str();
}

}  // namespace rcsplat
