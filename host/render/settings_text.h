// Settings from text, as the command line and other front ends give them: the indirect-light and bounce methods by
// name, a hemisphere "MxN", a spacing "MIN,MAX", and the quality presets. Each throws rcsplat::Error naming the
// option on bad input.
#pragma once
#include <functional>
#include <string>

#include "render/settings.h"

namespace rcsplat {

GiMethod parse_gi_method(const std::string& name);
BounceMethod parse_bounce_method(const std::string& name);
void parse_hemisphere(const std::string& text, CacheSettings& cache, bool fine = false);  // "MxN"
void parse_spacing(const std::string& text, CacheSettings& cache);     // "MIN,MAX"

constexpr const char* kDefaultQuality = "standard";  // the library's defaults

// --quality: draft, standard (the defaults) or final sets accuracy, rays per record, pixel and light samples, except
// those whose option was given (`given("--accuracy")`). quality_summary says what the request holds after it, for the
// summary, and whether given options replaced some of the preset's.
void apply_quality(const std::string& quality, RenderSettings& settings,
                   const std::function<bool(const char*)>& given);
std::string quality_summary(const std::string& quality, const RenderSettings& settings);
// What a preset sets, for the help text: "accuracy 0.6, 8x16 rays a record, one sample a pixel, 4 light samples".
std::string quality_preset_description(const std::string& quality);

}  // namespace rcsplat
