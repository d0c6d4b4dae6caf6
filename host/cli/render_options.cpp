// Parsing the render command's compound options.
#include <cstdio>

#include "cli/commands.h"
#include "util/error.h"

namespace rcsplat {

GiMethod parse_gi_method(const std::string& name) {
  for (GiMethod m : {GiMethod::none, GiMethod::splat, GiMethod::octree, GiMethod::path})
    if (name == gi_method_name(m)) return m;
  throw Error("--gi " + name + ": unknown method (use splat, octree, path or none)");
}

BounceMethod parse_bounce_method(const std::string& name) {
  for (BounceMethod m : {BounceMethod::automatic, BounceMethod::path, BounceMethod::photons})
    if (name == bounce_method_name(m)) return m;
  throw Error("--bounce-method " + name + ": unknown method (use auto, path or photons)");
}

void parse_hemisphere(const std::string& text, CacheSettings& cache, bool fine) {
  unsigned m = 0, n = 0;
  char tail = 0;
  std::string option = fine ? "--fine-hemisphere " : "--hemisphere ";
  if (std::sscanf(text.c_str(), "%ux%u%c", &m, &n, &tail) != 2 || m == 0 || n == 0)
    throw Error(option + text + ": expected MxN, for example 16x32");
  CacheSettings changed = cache;  // checked before it replaces the settings: a refused value leaves them as they were
  (fine ? changed.fine_theta_strata : changed.theta_strata) = m;
  (fine ? changed.fine_phi_strata : changed.phi_strata) = n;
  validate_cache_settings(changed);
  cache = changed;
}

void parse_spacing(const std::string& text, CacheSettings& cache) {
  float lo = 0, hi = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%f,%f%c", &lo, &hi, &tail) != 2)
    throw Error("--spacing " + text + ": expected MIN,MAX in pixels, for example 3,20");
  CacheSettings changed = cache;
  changed.min_reach_pixels = lo;
  changed.max_reach_pixels = hi;
  validate_cache_settings(changed);
  cache = changed;
}

}  // namespace rcsplat
