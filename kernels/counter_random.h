// Counter-based random numbers, compiled by both the kernels and the host: the same (a, b, c) gives the same number on
// every device and on the host, so a render is reproducible whatever the work-group order, and host references can
// draw the very samples a kernel drew.
#ifndef RCSPLAT_COUNTER_RANDOM_H
#define RCSPLAT_COUNTER_RANDOM_H
#include "shared_types.h"

inline rc_uint hash_u32(rc_uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

inline float random01(rc_uint a, rc_uint b, rc_uint c) {
  rc_uint h = hash_u32(a ^ hash_u32(b ^ hash_u32(c + 0x9e3779b9u)));
  return (float)(h >> 8) * (1.0f / 16777216.0f);  // 24 bits: strictly below 1
}

// The random streams: every place that draws numbers from the user's --seed draws from its own stream, so that no
// two of them correlate (a light guide that aimed where the records' own rays go would bias them). A stream's seed is
// the frame's seed XOR its salt (ASCII of a short name where there was one). Streams without a salt: the irradiance
// records (the seed itself), the direct light (hash_u32(pixel ^ hash_u32(seed)), kernels/direct.cl). Sequences of
// rounds step the seed by the golden ratio, STREAM_ROUND_STEP (path-traced rounds and batches).
#define STREAM_LIGHT_GUIDE 0x6c677569u        /* "lgui": the light guide's photons (render/indirect_guide.cpp) */
#define STREAM_PHOTON_MAP 0x70686f74u         /* "phot": the photon map's photons, XOR hash_u32(round) */
#define STREAM_CAUSTIC_MAP 0x63617573u        /* "caus": the caustic map's photons (render/indirect_caustics.cpp) */
#define STREAM_RADIANCE_RECORDS 0x68736831u   /* "hsh1": the radiance records' hemispheres and placement */
#define STREAM_PIXEL_JITTER 0x6a697474u       /* "jitt": path tracing's jitter over the pixel, + round */
#define STREAM_BOUNCE_PROBE 0x626f756eu       /* "boun": the bounce probe's photons (a fixed seed, not --seed's) */
#define STREAM_ENVIRONMENT_SHADOW 0x2545f491u /* shadow rays toward the environment's peak (kernels/direct.cl) */
#define STREAM_ENVIRONMENT_EXTRA 0x68e31da4u  /* the environment's extra randoms (kernels/environment.h) */
#define STREAM_GLOSSY 0x2c1b3c6du             /* glossy pixels' lobe samples (kernels/glossy.cl) */
#define STREAM_GLOSSY_STRATA 0x73747261u      /* "stra": their strata's scrambling per output pixel (glossy.cl) */
#define STREAM_LIGHT_STRATA 0x6c737472u       /* "lstr": the light samples' strata in rounds (direct.cl) */
#define STREAM_PATH 0x5bd1e995u               /* the path tracer's samples (kernels/path.cl) */
#define STREAM_GLASS_MIRROR 0x6d697272u       /* "mirr": lit surfaces seen in glass (kernels/glass_mirror.cl) */
#define STREAM_GLASS_CAUSTICS 0x676c6370u     /* "glcp": the glass caustic map's photons (passes/glass_caustics_pass) */
#define STREAM_ROUND_STEP 0x9e3779b9u         /* the golden ratio in 32 bits: seed + step * round */

#endif
